#include "tasks/lifelong_runner.hpp"

#include <utility>

#include "tasks/lifelong_run.hpp"

namespace tasks {

PlannerTimes summarize(std::vector<double> ms) { return planner::Latency::of(std::move(ms)); }

LifelongResult run_lifelong(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                            const std::string& solver, uint64_t seed, const LifelongOptions& opt)
{
  LifelongRun run(g, starts, tasks, solver, seed, opt);
  while (!run.done()) run.step();
  return run.finish();
}

}  // namespace tasks
