#include "tasks/lifelong_runner.hpp"

#include <utility>

#include "tasks/lifelong_epochs.hpp"
#include "tasks/lifelong_run.hpp"

namespace tasks {

std::vector<Event> advance_epoch(TaskManager& tasks, planner::RealtimePlanner& p, long t)
{
  std::vector<Event> events = tasks.update(t, p.current());
  if (!events.empty() || tasks.goals_changed()) start_epoch(tasks, p, tasks.goals());
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
