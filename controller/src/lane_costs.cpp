#include "controller/lane_costs.hpp"

#include <algorithm>
#include <cmath>

namespace controller {

std::vector<double> cell_speeds(const gridify::CellMap& map, double top_speed)
{
  auto lane_speed = [&](const std::string& lane) {
    auto it = map.lane_aisle.find(lane);
    if (it == map.lane_aisle.end()) return top_speed;
    const gridify::Aisle& a = map.aisles[static_cast<size_t>(it->second.first)];
    return it->second.second ? a.speed_ab : a.speed_ba;
  };
  std::vector<double> v(map.cells.size(), top_speed);
  for (size_t c = 0; c < map.cells.size(); ++c) {
    const gridify::Cell& cell = map.cells[c];
    if (cell.poses.empty()) continue;
    const bool junction = cell.kind == gridify::CellKind::Junction;
    double s = junction ? 0.0 : top_speed;
    for (const gridify::SumoPose& p : cell.poses)
      s = junction ? std::max(s, lane_speed(p.lane)) : std::min(s, lane_speed(p.lane));
    v[c] = std::min(s, top_speed);
  }
  return v;
}

std::vector<uint8_t> lane_costs(const gridify::CellMap& map, double top_speed)
{
  const std::vector<double> v = cell_speeds(map, top_speed);
  const double fast = v.empty() ? top_speed : *std::max_element(v.begin(), v.end());
  std::vector<uint8_t> cost(v.size(), 1);
  for (size_t c = 0; c < v.size(); ++c)
    if (v[c] > 0) cost[c] = static_cast<uint8_t>(std::clamp(std::ceil(fast / v[c] - 1e-9), 1.0, 255.0));
  return cost;
}

}  // namespace controller
