#include "controller/rule_check.hpp"

#include <algorithm>
#include <cstdio>

#include "controller/sumo_error.hpp"

namespace controller {

void RuleCheck::excuse(int i, std::vector<planner::Vertex> cells)
{
  if (excused_.size() <= static_cast<size_t>(i)) excused_.resize(i + 1);
  excused_[i] = std::move(cells);
}

void RuleCheck::check(const std::vector<VehiclePose>& poses, const std::vector<std::string>& ids, double t)
{
  ++checks_;
  // Nothing closed and no zone: nothing to violate (every libsumo run watches lanes). The
  // next check with something closed starts afresh: at a tick boundary every AGV stands on
  // its cell, and none crosses half a cell within one SUMO step.
  if (!rules_.anything_closed() && rules_.zones().empty()) {
    last_.clear();
    return;
  }
  char when[48];
  std::snprintf(when, sizeof when, "t=%.3f s: ", t);
  std::vector<planner::Vertex> at(poses.size(), -1);
  for (size_t i = 0; i < poses.size(); ++i) at[i] = map_.locate(poses[i].lane, poses[i].pos);
  const std::vector<uint8_t>& closed = rules_.closed();
  if (excused_.size() != at.size()) excused_.resize(at.size());
  auto excused = [&](size_t i, planner::Vertex v) {
    return std::find(excused_[i].begin(), excused_[i].end(), v) != excused_[i].end();
  };
  if (last_.size() == at.size())
    for (size_t i = 0; i < at.size(); ++i) {
      const planner::Vertex v = at[i], u = last_[i];
      if (!excused_[i].empty() && excused(i, u) && !excused(i, v)) excused_[i].clear();  // left them
      if (v >= 0 && v != u && closed[v] && (u < 0 || !closed[u]) && !excused(i, v))
        throw ControlError(when + ids[i] + " entered closed cell " + std::to_string(v) + " (" + poses[i].lane +
                           ", closed by " + rules_.closed_by(v) + ")");
      if (v >= 0 && u >= 0 && v != u && rules_.arc_closed(u, v) && !excused(i, v))
        throw ControlError(when + ids[i] + " drove cell " + std::to_string(u) + " -> " + std::to_string(v) + " (" +
                           poses[i].lane + ") against a one-direction closure (" + rules_.arc_closed_by(u, v) + ")");
    }
  last_ = at;
  const std::vector<Zone>& zones = rules_.zones();
  if (zones.empty()) return;
  std::vector<int> first(zones.size(), -1);
  for (size_t i = 0; i < at.size(); ++i) {
    if (at[i] < 0) continue;
    for (int z : rules_.zones_of()[at[i]]) {
      if (first[z] < 0) {
        first[z] = static_cast<int>(i);
        continue;
      }
      throw ControlError(std::string(when) + "zone '" + zones[z].id + "' (" + zones[z].what + ") holds two AGVs: " + ids[first[z]] +
                         " and " + ids[i] + " (one at a time)");
    }
  }
}

}  // namespace controller
