#include "controller/safety.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "controller/sumo_error.hpp"

namespace controller {

Safety::Safety(const gridify::CellMap& map, double length)
    : map_(map), length_(length), owner_(map.graph.size(), -1), stamp_(map.graph.size(), 0)
{
}

Claim Safety::locate(const std::string& lane, double pos) const
{
  auto it = map_.lane_aisle.find(lane);
  if (it == map_.lane_aisle.end()) return {};
  const gridify::Aisle& a = map_.aisles[it->second.first];
  // Offset from junction A in cells.
  const double k = (it->second.second ? pos : a.length_ba - pos) / a.spacing;
  const double kc = std::min<double>(std::max(k, 0.0), a.steps);
  const double r = std::round(kc);
  if (std::fabs(kc - r) * a.spacing <= 1e-6) return {a.cells[static_cast<size_t>(r)], -1};
  const size_t lo = static_cast<size_t>(std::floor(kc));
  return {a.cells[lo], a.cells[std::min(lo + 1, a.cells.size() - 1)]};
}

void Safety::check(const std::vector<VehiclePose>& poses, const std::vector<std::vector<planner::Vertex>>& allowed,
                   const std::vector<std::string>& ids, double t, bool exclusive)
{
  ++checks_;
  ++epoch_;
  char when[64];
  std::snprintf(when, sizeof when, "t=%.3f s: ", t);
  std::unordered_map<std::string, std::vector<std::pair<std::pair<double, double>, int>>> on_lane;
  for (int i = 0; i < static_cast<int>(poses.size()); ++i) {
    const Claim c = locate(poses[i].lane, poses[i].pos);
    if (c.a < 0)
      throw ControlError(when + std::string("AGV ") + ids[i] + " is off the aisles (lane '" + poses[i].lane + "')");
    for (planner::Vertex v : {c.a, c.b}) {
      if (v < 0) continue;
      const auto& al = allowed[i];
      if (std::find(al.begin(), al.end(), v) == al.end())
        throw ControlError(when + std::string("AGV ") + ids[i] + " is at cell " + std::to_string(v) + " (lane " +
                           poses[i].lane + " pos " + std::to_string(poses[i].pos) +
                           "), not on its committed path");
      if (exclusive || c.b < 0) {
        if (stamp_[v] == epoch_)
          throw ControlError(when + std::string("AGVs ") + ids[owner_[v]] + " and " + ids[i] + " overlap at cell " +
                             std::to_string(v));
        stamp_[v] = epoch_;
        owner_[v] = i;
      }
    }
    // The body on its lane: [front - length, front].
    on_lane[poses[i].lane].push_back({{poses[i].pos - length_, poses[i].pos}, i});
  }
  for (auto& [lane, l] : on_lane) {
    std::sort(l.begin(), l.end());
    size_t far = 0;  // the body reaching furthest so far
    for (size_t k = 1; k < l.size(); ++k) {
      if (l[k].first.first < l[far].first.second - 1e-9)
        throw ControlError(when + std::string("AGVs ") + ids[l[far].second] + " and " + ids[l[k].second] +
                           " overlap on lane " + lane + " (bodies intersect)");
      if (l[k].first.second > l[far].first.second) far = k;
    }
  }
}

}  // namespace controller
