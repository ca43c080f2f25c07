#include "tasks/lorr_problem.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <vector>
#include <nlohmann/json.hpp>

#include "planner/error.hpp"

namespace tasks {
namespace {

using nlohmann::json;
using planner::input_error;

std::string dir_of(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string stem_of(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  const auto dot = base.find_last_of('.');
  return dot == std::string::npos ? base : base.substr(0, dot);
}

json read_json(const std::string& path)
{
  planner::check_not_directory(path);
  std::ifstream in(path);
  if (!in) throw input_error(path, 0, "cannot open file");
  // A key given twice in one object: nlohmann keeps the last silently ("mapFile" twice read
  // the second); the LoRR start kit's reader may keep either, so name it instead.
  std::vector<std::set<std::string>> keys;  // per open object
  std::string dup;
  const json::parser_callback_t check = [&](int, json::parse_event_t ev, json& parsed) {
    if (ev == json::parse_event_t::object_start) keys.emplace_back();
    else if (ev == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    else if (ev == json::parse_event_t::key && !keys.empty() && !keys.back().insert(parsed.get<std::string>()).second &&
             dup.empty())
      dup = parsed.get<std::string>();
    return true;
  };
  try {
    json j = json::parse(in, check);
    if (!dup.empty()) throw input_error(path, 0, "key '" + dup + "' appears twice in one object");
    return j;
  } catch (const json::exception& e) {
    // parse_error, but also out_of_range for a number like 1e400: without the catch its
    // message named no file. nlohmann reports a byte offset; keep the message on one line.
    throw input_error(path, 0, std::string("invalid JSON: ") + e.what());
  }
}

std::string string_field(const json& j, const std::string& path, const char* key)
{
  if (!j.contains(key)) throw input_error(path, 0, std::string("missing field '") + key + "'");
  if (!j[key].is_string()) throw input_error(path, 0, std::string("field '") + key + "' must be a string");
  return j[key].get<std::string>();
}

// simulation_time.json keys are the instance names without the round prefix ("I-04" for
// MR23-I-04); the longest key that ends the stem wins.
long lookup_steps(const std::string& problem_dir, const std::string& stem)
{
  for (const std::string& d : {problem_dir, problem_dir + "../"}) {
    const std::string f = d + "simulation_time.json";
    std::ifstream in(f);
    if (!in) continue;
    const json j = read_json(f);
    // key() below throws json::invalid_iterator, naming no file, on an array.
    if (!j.is_object()) throw input_error(f, 0, "expected a JSON object of instance name -> steps");
    const json* best = nullptr;
    std::string best_key;
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string& k = it.key();
      if (k.size() <= stem.size() && stem.compare(stem.size() - k.size(), k.size(), k) == 0 && k.size() > best_key.size())
        best = &*it, best_key = k;
    }
    if (!best) continue;
    // The entry is there: a bad value is its error, not "no entry" (which told the user
    // to pass --steps although the file had the key).
    if (!best->is_number_integer() || best->get<long long>() <= 0 || best->get<long long>() > 1000000000)
      throw input_error(f, 0, "'" + best_key + "': steps must be an integer in [1, 1000000000], not " + best->dump());
    return best->get<long>();
  }
  return -1;
}

}  // namespace

int LorrProblem::pool_size() const
{
  const double r = num_tasks_reveal * team_size;  // 2023 roundrobin files say 1: one per agent
  return std::max(team_size, static_cast<int>(std::floor(r + 1e-9)));
}

LorrProblem load_lorr_problem(const std::string& path)
{
  const json j = read_json(path);
  if (!j.is_object()) throw input_error(path, 0, "expected a JSON object");
  LorrProblem p;
  p.path = path;
  p.name = stem_of(path);
  const std::string dir = dir_of(path);
  // Relative to the problem file, as the LoRR start kit reads them; an absolute path as is.
  auto file = [&](const char* key) {
    const std::string f = string_field(j, path, key);
    return !f.empty() && f[0] == '/' ? f : dir + f;
  };
  p.map_file = file("mapFile");
  p.agent_file = file("agentFile");
  p.task_file = file("taskFile");
  if (!j.contains("teamSize") || !j["teamSize"].is_number_integer() || j["teamSize"].get<long long>() <= 0 ||
      j["teamSize"].get<long long>() > 1000000)
    throw input_error(path, 0, "field 'teamSize' must be a positive integer");
  p.team_size = j["teamSize"].get<int>();
  if (j.contains("numTasksReveal")) {
    if (!j["numTasksReveal"].is_number() || !(j["numTasksReveal"].get<double>() > 0))
      throw input_error(path, 0, "field 'numTasksReveal' must be a positive number");
    p.num_tasks_reveal = j["numTasksReveal"].get<double>();
    // The pool holds numTasksReveal x teamSize tasks: bound it as the YAML tasks.pool_size
    // is (4.3e10 x 100 overflowed pool_size()'s int; 1e7 x 100 tasks would not fit in memory).
    if (p.num_tasks_reveal * p.team_size > 1e7)
      throw input_error(path, 0, "field 'numTasksReveal' x teamSize must be at most 10000000 tasks");
  }
  if (j.contains("version")) p.year = 2024;
  if (j.contains("taskAssignmentStrategy")) p.strategy = string_field(j, path, "taskAssignmentStrategy");
  p.simulation_time = lookup_steps(dir, p.name);
  return p;
}

}  // namespace tasks
