#include "planner/plan_io.hpp"

#include <cmath>
#include <sstream>

namespace planner {
namespace {

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
  for (size_t t = 0; t < plan.size(); ++t) {
    out << t << ':';
    config_line(out, g, plan[t]);
  }
}

}  // namespace planner
