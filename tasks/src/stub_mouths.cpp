#include "tasks/stub_mouths.hpp"

#include <algorithm>

#include "tasks/battery.hpp"

namespace tasks {

std::vector<planner::Vertex> stub_mouths(const planner::Graph& g, const std::vector<planner::Vertex>& stations)
{
  std::vector<planner::Vertex> mouths;
  std::vector<uint8_t> seen(g.size(), 0);
  for (planner::Vertex s : stations) {
    if (seen[s]) continue;
    const std::vector<planner::Vertex> corridor = dead_end_corridor(g, s);
    for (planner::Vertex c : corridor) seen[c] = 1;
    auto outside = [&](planner::Vertex u) { return std::find(corridor.begin(), corridor.end(), u) == corridor.end(); };
    for (planner::Vertex c : corridor) {
      std::vector<planner::Vertex> around(g.neighbors(c).begin(), g.neighbors(c).end());
      around.insert(around.end(), g.in_neighbors(c).begin(), g.in_neighbors(c).end());
      for (planner::Vertex u : around)
        if (outside(u) && std::find(mouths.begin(), mouths.end(), u) == mouths.end()) mouths.push_back(u);
    }
  }
  return mouths;
}

std::vector<uint8_t> mouth_costs(const planner::Graph& g, const std::vector<planner::Vertex>& stations, int cost)
{
  std::vector<uint8_t> c = g.weighted() ? g.move_costs() : std::vector<uint8_t>(g.size(), 1);
  if (cost <= 0) return c;
  for (planner::Vertex m : stub_mouths(g, stations)) c[m] = static_cast<uint8_t>(std::min(255, c[m] + cost));
  return c;
}

}  // namespace tasks
