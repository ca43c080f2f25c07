#include "tasks/urgency.hpp"

#include <algorithm>
#include <unordered_map>

#include "tasks/escalation.hpp"
#include "tasks/station_queues.hpp"
#include "tasks/task_manager.hpp"

namespace tasks {

bool battery_urgent(const TaskManager& tm, int a)
{
  const Battery* b = tm.urgency().battery ? tm.battery() : nullptr;
  return b && (b->charging(a) || (tm.busy(a) && b->low(a)));
}

std::vector<float> priority_hints(const TaskManager& tm, const planner::Config* positions)
{
  const UrgencyOptions& o = tm.urgency();
  const StationQueues* q = tm.queues();
  const bool leavers_first = q && q->options().leavers_first && q->options().clear_after > 0 && positions;
  if (!o.on() && !leavers_first) return {};
  const int n = tm.num_agents();
  std::vector<float> h(n, 0.0f);
  if (o.head_after > 0 && !o.stalls && tm.stalls() && positions) {
    // The head of each errand cell's crowd: its most stalled heading agent outside the
    // cell's pocket, if >= head_after (with drop_hints, every such agent with a load on
    // board); and every agent on its way out of a pocket.
    const planner::Config& at = *positions;
    std::unordered_map<planner::Vertex, std::pair<long long, int>> head;  // cell -> (stall, agent)
    for (int a = 0; a < n; ++a) {
      const planner::Vertex p = tm.pocket(at[a]);
      if (p >= 0 && tm.pocket(tm.goals()[a]) != p) {
        h[a] = kLeavingUrgency;
        continue;
      }
      if (!tm.heading(a) || p >= 0) continue;
      const long long s = tm.stalls()->stalled(tm.now(), tm.task_of(a)->id);
      if (s < o.head_after) continue;
      if (o.drop_hints && tm.task_of(a)->opened()) {  // a load on board: every stalled one
        h[a] = static_cast<float>(s);
        continue;
      }
      auto& hd = head[tm.task_of(a)->next_cell()];
      if (s > hd.first || (s == hd.first && a < hd.second)) hd = {s, a};
    }
    for (const auto& [cell, hd] : head) h[hd.second] = static_cast<float>(hd.first);
  }
  const ErrandStalls* st = o.stalls ? tm.stalls() : nullptr;
  const Battery* b = o.battery ? tm.battery() : nullptr;
  for (int a = 0; a < n; ++a) {
    if (st && tm.heading(a)) h[a] = static_cast<float>(st->stalled(tm.now(), tm.task_of(a)->id));
    if (b && battery_urgent(tm, a)) {
      const double f = std::clamp(b->charge(a) / b->options().capacity_wh, 0.0, 1.0);
      h[a] = std::max(h[a], kBatteryUrgency + static_cast<float>(kBatteryUrgency * (1.0 - f)));
    }
  }
  if (positions) escalation_hints(tm, *positions, h);  // the starvation guard (escalation.hpp): above the rest but battery
  if (leavers_first)  // StationQueues::leavers_first: out of a clearing station's pocket first
    for (int a = 0; a < n; ++a) {
      const int i = q->pocket_of((*positions)[a]);
      if (i >= 0 && q->clearing(i) && q->pocket_of(tm.goals()[a]) != i) h[a] = std::max(h[a], kLeavingUrgency);
    }
  return h;
}

void hint_pockets(const TaskManager& tm, planner::RealtimePlanner& p)
{
  const int cost = tm.urgency().pocket_cost;
  // Also at cost 0 (off for every cost rule): epibt's pocket exit rule needs the labels alone.
  if (!tm.dead_end_pockets().empty()) p.set_pockets(tm.dead_end_pockets(), static_cast<float>(std::max(0, cost)));
}

}  // namespace tasks
