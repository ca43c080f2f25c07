#include "tasks/urgency.hpp"

#include <algorithm>

#include "tasks/task_manager.hpp"

namespace tasks {

bool battery_urgent(const TaskManager& tm, int a)
{
  const Battery* b = tm.urgency().battery ? tm.battery() : nullptr;
  return b && (b->charging(a) || (tm.busy(a) && b->low(a)));
}

std::vector<float> priority_hints(const TaskManager& tm)
{
  const UrgencyOptions& o = tm.urgency();
  if (!o.on()) return {};
  const int n = tm.num_agents();
  std::vector<float> h(n, 0.0f);
  const ErrandStalls* st = o.stalls ? tm.stalls() : nullptr;
  const Battery* b = o.battery ? tm.battery() : nullptr;
  for (int a = 0; a < n; ++a) {
    if (st && tm.heading(a)) h[a] = static_cast<float>(st->stalled(tm.now(), tm.task_of(a)->id));
    if (b && battery_urgent(tm, a)) {
      const double f = std::clamp(b->charge(a) / b->options().capacity_wh, 0.0, 1.0);
      h[a] = kBatteryUrgency + static_cast<float>(kBatteryUrgency * (1.0 - f));
    }
  }
  return h;
}

}  // namespace tasks
