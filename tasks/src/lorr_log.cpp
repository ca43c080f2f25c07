// lorr_log: the PlanViz / LoRR fields of a lifelong log (see lifelong_log.hpp).
#include <algorithm>
#include <tuple>
#include <stdexcept>
#include <unordered_map>

#include "tasks/lifelong_log.hpp"

namespace tasks {
namespace {

std::string joined(const std::string& letters)
{
  std::string s;
  s.reserve(letters.size() * 2);
  for (char c : letters) {
    if (!s.empty()) s += ',';
    s += c;
  }
  return s;
}

// "t:task,..." per agent; t = the step whose move first serves it (LoRR records an
// assignment made after step t's completions at t + 1), one entry per change.
nlohmann::json schedules(const TaskManager& tasks)
{
  std::vector<std::vector<std::pair<long, long>>> per(static_cast<size_t>(tasks.num_agents()));
  for (const Assignment& a : tasks.assignments()) {
    auto& v = per[static_cast<size_t>(a.agent)];
    if (!v.empty() && v.back().first == a.t + 1) v.pop_back();  // the last change of a step wins
    if (v.empty() || v.back().second != a.task) v.push_back({a.t + 1, a.task});
  }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& v : per) {
    std::string s;
    for (const auto& [t, task] : v) {
      if (!s.empty()) s += ',';
      s += std::to_string(t) + ":" + std::to_string(task);
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace

nlohmann::json lorr_log(const RunInfo& info, const LifelongResult& r, const TaskManager& tasks, const planner::Graph& g)
{
  if (!g.is_grid()) throw std::invalid_argument("lorr_log needs a grid graph");
  if (r.actions.size() != r.starts.size()) throw std::invalid_argument("lorr_log needs the recorded actions");
  nlohmann::json j = lifelong_log(info, r);
  const bool pool = info.mode == "pool";
  j["version"] = pool ? "2024 LoRR" : "2023 LoRR";
  j["AllValid"] = r.planner_errors == 0 ? "Yes" : "No";
  j["numScheduleErrors"] = 0;
  j["numEntryTimeouts"] = 0;
  nlohmann::json start = nlohmann::json::array();
  for (planner::Vertex v : r.starts) start.push_back({g.cell_y(v), g.cell_x(v), "E"});  // LoRR: all face east
  j["start"] = std::move(start);
  nlohmann::json paths = nlohmann::json::array();
  for (const std::string& a : r.actions) paths.push_back(joined(a));
  j["actualPaths"] = paths;
  j["plannerPaths"] = std::move(paths);  // the executor runs exactly what was planned
  nlohmann::json errors = nlohmann::json::array();
  if (r.planner_errors > 0) errors.push_back({-1, -1, r.first_error_t, r.first_error});
  j["errors"] = std::move(errors);

  const TaskFile& file = tasks.file();
  auto cell = [&](planner::Vertex v) { return std::pair<int, int>{g.cell_y(v), g.cell_x(v)}; };
  if (pool) {
    nlohmann::json ts = nlohmann::json::array();
    for (const TaskRecord& t : tasks.revealed_tasks()) {
      nlohmann::json locs = nlohmann::json::array();
      for (planner::Vertex v : file.tasks[static_cast<size_t>(t.line)]) {
        locs.push_back(cell(v).first);
        locs.push_back(cell(v).second);
      }
      ts.push_back({t.id, t.revealed, std::move(locs)});
    }
    j["tasks"] = std::move(ts);
    j["actualSchedule"] = schedules(tasks);
    j["plannerSchedule"] = schedules(tasks);
    return j;
  }
  // 2023: LoRR numbers tasks in assignment order (agent order within a step).
  struct Row {
    long t;
    int kind;  // 0 finished, 1 assigned: a task finished at t comes before the next one assigned at t
    nlohmann::json e;
  };
  std::vector<std::vector<Row>> per(static_cast<size_t>(tasks.num_agents()));
  std::unordered_map<long, int> line_of;
  for (const TaskRecord& t : tasks.revealed_tasks()) line_of[t.id] = t.line;
  std::unordered_map<long, long> lorr_id;
  nlohmann::json ts = nlohmann::json::array();
  for (const Assignment& a : tasks.assignments()) {
    if (a.task < 0) continue;
    const long id = static_cast<long>(lorr_id.size());
    lorr_id[a.task] = id;
    const auto [row, col] = cell(file.tasks[static_cast<size_t>(line_of.at(a.task))].front());
    ts.push_back({id, row, col});
    per[static_cast<size_t>(a.agent)].push_back({a.t, 1, {id, a.t, "assigned"}});
  }
  for (const Event& e : r.events) per[static_cast<size_t>(e.agent)].push_back({e.t, 0, {lorr_id.at(e.task), e.t, "finished"}});
  nlohmann::json ev = nlohmann::json::array();
  for (auto& rows : per) {
    std::stable_sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) { return std::tie(x.t, x.kind) < std::tie(y.t, y.kind); });
    nlohmann::json list = nlohmann::json::array();
    for (Row& row : rows) list.push_back(std::move(row.e));
    ev.push_back(std::move(list));
  }
  j["events"] = std::move(ev);
  j["tasks"] = std::move(ts);
  return j;
}

}  // namespace tasks
