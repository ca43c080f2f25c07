#include "tasks/lifelong_goal.hpp"

#include <algorithm>

#include "tasks/escalation.hpp"
#include "tasks/task_manager.hpp"
#include "tasks/urgency.hpp"

namespace tasks {

planner::GoalTest lifelong_goal_test(const planner::Config& goals, const planner::Config& positions,
                                     const std::vector<char>& busy)
{
  struct Pending {
    int agent;
    planner::Vertex goal;
  };
  std::vector<Pending> pending;
  for (size_t i = 0; i < goals.size(); ++i)
    if (busy[i] && positions[i] != goals[i]) pending.push_back({static_cast<int>(i), goals[i]});
  if (pending.empty()) return [](const planner::Vertex*) { return true; };
  return [pending = std::move(pending)](const planner::Vertex* c) {
    for (const Pending& p : pending)
      if (c[p.agent] == p.goal) return true;
    return false;
  };
}

planner::GoalTest lifelong_goal_test(const TaskManager& tasks, const planner::Config& positions)
{
  std::vector<char> busy(tasks.num_agents());
  for (int a = 0; a < tasks.num_agents(); ++a) busy[a] = tasks.awaited(a);
  // Battery urgency (urgency.hpp): while a low agent is off its goal, the epoch waits for a
  // low one, so the search plans a way for it, not for whoever arrives first.
  std::vector<char> urgent(tasks.num_agents());
  bool any = false;
  for (int a = 0; a < tasks.num_agents(); ++a) {
    urgent[a] = busy[a] && battery_urgent(tasks, a);
    any = any || (urgent[a] && positions[a] != tasks.goals()[a]);
  }
  // Escalation (escalation.hpp): else while an escalated agent is off its goal, the epoch
  // waits for the longest-stalled of them (waiting for any of them, three escalated errands
  // head-on at one junction jammed small_rules_lifelong, seed 3, 4000 ticks: K 904 -> 450).
  if (!any)
    if (const int top = escalation_focus(tasks, positions); top >= 0) {
      std::fill(urgent.begin(), urgent.end(), 0);
      urgent[top] = 1;
      any = true;
    }
  return lifelong_goal_test(tasks.goals(), positions, any ? urgent : busy);
}

}  // namespace tasks
