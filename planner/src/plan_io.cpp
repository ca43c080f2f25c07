#include "planner/plan_io.hpp"

#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "planner/error.hpp"

namespace planner {
namespace {

// "(x,y)" at s[p]: true with both coordinates, false if malformed or out of int range
// (sscanf's %d wraps: 4294967299 read as 3, and a bad plan passed as valid).
bool parse_cell(const std::string& s, size_t p, int& x, int& y)
{
  auto number = [&](size_t& i, int& out) {
    while (i < s.size() && s[i] == ' ') ++i;  // as %d did
    const char* first = s.data() + i;
    const char* last = s.data() + s.size();
    long long v = 0;
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || v < INT_MIN || v > INT_MAX) return false;
    out = static_cast<int>(v);
    i += static_cast<size_t>(end - first);
    return true;
  };
  if (s[p] != '(') return false;
  ++p;
  if (!number(p, x) || p >= s.size() || s[p] != ',') return false;
  ++p;
  return number(p, y) && p < s.size() && s[p] == ')';
}

std::string cell(const Graph& g, Vertex v)
{
  std::ostringstream s;
  if (g.is_grid()) s << '(' << g.cell_x(v) << ',' << g.cell_y(v) << ')';
  else if (g.has_positions()) s << '(' << g.position(v).x << ',' << g.position(v).y << ')';
  else s << '(' << v << ",0)";
  return s.str();
}

void config_line(std::ostream& out, const Graph& g, const Config& c)
{
  for (size_t i = 0; i < c.size(); ++i) out << cell(g, c[i]) << ',';
  out << '\n';
}

}  // namespace

void write_plan(std::ostream& out, const Graph& g, const Config& starts, const Config& goals,
                const std::vector<Config>& plan, const PlanHeader& h)
{
  write_plan_header(out, g, starts, goals, h);
  write_plan_steps(out, g, plan, 0);
}

void write_plan_header(std::ostream& out, const Graph& g, const Config& starts, const Config& goals,
                       const PlanHeader& h)
{
  out << "agents=" << starts.size() << '\n'
      << "map_file=" << h.map_file << '\n'
      << "solver=" << h.solver << '\n'
      << "solved=" << (h.solved ? 1 : 0) << '\n'
      << "soc=" << h.soc << '\n'
      << "soc_lb=" << h.soc_lb << '\n'
      << "makespan=" << h.makespan << '\n'
      << "comp_time=" << std::llround(h.comp_time_ms) << '\n';
  for (auto& [k, v] : h.extra) out << k << '=' << v << '\n';
  out << "starts=";
  config_line(out, g, starts);
  out << "goals=";
  config_line(out, g, goals);
  out << "solution=\n";
}

void write_plan_steps(std::ostream& out, const Graph& g, const std::vector<Config>& plan, size_t first_t)
{
  for (size_t t = 0; t < plan.size(); ++t) {
    out << first_t + t << ':';
    config_line(out, g, plan[t]);
  }
}

std::vector<Config> read_plan(std::istream& in, const Graph& g, const std::string& source)
{
  std::vector<Config> plan;
  std::string line;
  int no = 0;
  bool in_solution = false;
  while (std::getline(in, line)) {
    ++no;
    if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF plans, as the map/scen readers
    if (no == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);  // and a UTF-8 byte order mark
    if (!in_solution) {
      in_solution = line.rfind("solution=", 0) == 0;
      continue;
    }
    if (line.empty()) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) throw input_error(source, no, "expected 't:(x,y),...'");
    Config c;
    size_t p = colon + 1;
    while ((p = line.find('(', p)) != std::string::npos) {
      int x = 0, y = 0;
      if (!parse_cell(line, p, x, y)) {
        const size_t close = line.find(')', p);
        throw input_error(source, no, "expected '(x,y)' with integer coordinates, not '" +
                                          line.substr(p, close == std::string::npos ? 24 : close - p + 1) + "'");
      }
      const Vertex v = g.at(x, y);
      if (v < 0) throw input_error(source, no, "cell (" + std::to_string(x) + "," + std::to_string(y) + ") is off the map");
      c.push_back(v);
      ++p;
    }
    const std::string t = line.substr(0, colon);
    if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos || std::to_string(plan.size()) != t)
      throw input_error(source, no, "timestep '" + t + "', expected " + std::to_string(plan.size()));
    plan.push_back(std::move(c));
  }
  if (!in_solution) throw input_error(source, 0, "no 'solution=' line");
  return plan;
}

}  // namespace planner
