#include "tasks/lifelong_runner.hpp"

#include <utility>

#include "tasks/lifelong_goal.hpp"
#include "tasks/lifelong_run.hpp"
#include "tasks/urgency.hpp"

namespace tasks {

std::vector<Event> advance_epoch(TaskManager& tasks, planner::RealtimePlanner& p, long t)
{
  std::vector<Event> events = tasks.update(t, p.current());
  if (!events.empty() || tasks.goals_changed()) hint_priorities(tasks, p);
  if (!events.empty() || tasks.goals_changed()) p.set_goals(tasks.goals(), lifelong_goal_test(tasks, p.current()));
  return events;
}

PlannerTimes summarize(std::vector<double> ms) { return planner::Latency::of(std::move(ms)); }

LifelongResult run_lifelong(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                            const std::string& solver, uint64_t seed, const LifelongOptions& opt)
{
  LifelongRun run(g, starts, tasks, solver, seed, opt);
  while (!run.done()) run.step();
  return run.finish();
}

}  // namespace tasks
