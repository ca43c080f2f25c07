#include "planner/lacam/runner.hpp"

#include <algorithm>

#include "planner/latency.hpp"
#include "planner/validator.hpp"

namespace planner {

RunResult run_realtime(RealtimePlanner& p, const Graph& g, const Config& starts, const Config& goals,
                       const RunOptions& opt)
{
  RunResult r;
  Validator val(g, starts, goals);
  std::vector<double> times, cpu_times;
  if (opt.record_plan) r.plan.push_back(starts);
  while (true) {
    if (p.at_goal()) {
      r.solved = true;
      break;
    }
    if (r.total_planning_ms > opt.timeout_ms) {
      r.timed_out = true;
      break;
    }
    if (r.iterations >= opt.max_steps) {
      r.step_limit = true;
      break;
    }
    const auto t0 = Clock::now();
    const double c0 = thread_cpu_ms();
    p.search(opt.per_iteration);
    p.next();
    p.commit();
    const double dt = ms_since(t0);
    const double dc = thread_cpu_ms() - c0;
    times.push_back(dt);
    cpu_times.push_back(dc);
    r.max_iteration_cpu_ms = std::max(r.max_iteration_cpu_ms, dc);
    r.total_planning_ms += dt;
    r.max_iteration_ms = std::max(r.max_iteration_ms, dt);
    ++r.iterations;
    if (p.exhausted()) {
      r.no_solution = true;
      break;
    }
    if (!val.step(p.current())) {
      r.validation_error = val.error();
      break;
    }
    if (opt.record_plan) r.plan.push_back(p.current());
    if (opt.on_progress) {
      r.expansions = p.expansions();
      opt.on_progress(r);
    }
  }
  r.p99_iteration_ms = Latency::of(std::move(times)).p99;
  r.p99_iteration_cpu_ms = Latency::of(std::move(cpu_times)).p99;
  r.soc = val.sum_of_costs();
  r.sum_of_loss = val.sum_of_loss();
  r.makespan = val.steps();
  r.expansions = p.expansions();
  r.explored = p.explored();
  return r;
}

RunResult run_full_horizon(const Graph& g, const Config& starts, const Config& goals, LacamOptions lopt,
                           const RunOptions& opt, ActionPreference* pref)
{
  RunResult r;
  const auto t0 = Clock::now();
  DistTable dist(g);
  Lacam lacam(g, dist, lopt, pref);
  lacam.reset(starts, goals);
  if (!opt.on_progress) {
    lacam.search(Budget::time_ms(opt.timeout_ms), true);
  } else {
    // The same search in slices (search() continues where it stopped), reporting between them.
    while (lacam.search(Budget::time_ms(std::min(opt.progress_ms, opt.timeout_ms - ms_since(t0))), true) ==
               Status::Searching &&
           ms_since(t0) < opt.timeout_ms) {
      r.total_planning_ms = ms_since(t0);
      r.expansions = lacam.expansions();
      r.explored = lacam.explored();
      opt.on_progress(r);
    }
  }
  const double left_ms = std::min(opt.anytime_ms, opt.timeout_ms) - ms_since(t0);
  if (lacam.refining() && left_ms > 0) lacam.search(Budget::time_ms(left_ms));
  r.total_planning_ms = r.max_iteration_ms = r.p99_iteration_ms = ms_since(t0);
  r.iterations = 1;
  r.expansions = lacam.expansions();
  r.explored = lacam.explored();
  r.no_solution = lacam.status() == Status::NoSolution;
  r.timed_out = lacam.status() == Status::Searching;
  if (lacam.status() != Status::Solved) return r;
  std::vector<Config> path = lacam.best_path();
  Validator val(g, starts, goals);
  for (size_t t = 1; t < path.size(); ++t)
    if (!val.step(path[t])) {
      r.validation_error = val.error();
      return r;
    }
  r.solved = true;
  r.soc = val.sum_of_costs();
  r.sum_of_loss = val.sum_of_loss();
  r.makespan = val.steps();
  if (opt.record_plan) r.plan = std::move(path);
  return r;
}

}  // namespace planner
