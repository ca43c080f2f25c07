#include "tasks/lifelong_exec.hpp"

#include "tasks/lifelong_run.hpp"

namespace tasks {

LifelongExecResult run_lifelong_exec(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                                     const std::string& solver, uint64_t seed, const LifelongOptions& opt,
                                     const executor::DelaySpec& delays, const executor::ExecOptions& exec)
{
  LifelongOptions o = opt;
  o.graph_execution = true;
  o.exec = exec;
  o.delays = delays;
  LifelongRun run(g, starts, tasks, solver, seed, o);
  while (!run.done()) run.step();
  LifelongExecResult out;
  out.max_gap = run.max_gap();
  out.exec = run.exec_stats();
  out.life = run.finish();
  return out;
}

}  // namespace tasks
