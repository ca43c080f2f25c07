#pragma once
// Runner: the paper's experiment loop. A real-time planner plans with the per-iteration
// budget, the agents execute the first step, repeat -- until the goal test holds, the
// cumulative planning time passes the timeout, or a step limit is reached. Full-horizon
// LaCAM plans once and executes the whole path. Every executed step goes through the
// Validator.
#include <functional>
#include <string>
#include <vector>

#include "planner/budget.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/realtime_planner.hpp"

namespace planner {

struct RunResult;

struct RunOptions {
  Budget per_iteration = Budget::time_ms(1.0);
  double timeout_ms = 60000;     // cumulative planning time
  long long max_steps = 100000;  // executed steps
  bool record_plan = true;       // keep every configuration (for --out)
  // Progress: called with the result so far after every iteration (full horizon: about
  // every progress_ms of search). Empty: no calls, and LaCAM searches in one piece.
  std::function<void(const RunResult&)> on_progress;
  double progress_ms = 1000;
  // Full-horizon LaCAM with LacamOptions::refine: after the first solution, LaCAM* keeps
  // refining until this much planning time has passed in all (the "refine-after-solve"
  // variant; 0 = execute the first solution).
  double anytime_ms = 0;
};

struct RunResult {
  bool solved = false;
  bool no_solution = false;      // the search proved the instance unsolvable
  bool timed_out = false;        // cumulative planning time > timeout
  bool step_limit = false;
  std::string validation_error;  // "" when every executed step is valid
  double total_planning_ms = 0;
  double max_iteration_ms = 0, p99_iteration_ms = 0;
  // The same on the planning thread's CPU time (what a loaded machine's preemption does not
  // inflate); full horizon: 0.
  double max_iteration_cpu_ms = 0, p99_iteration_cpu_ms = 0;
  long long iterations = 0;
  long long soc = 0, makespan = 0;  // soc: standard (Validator::sum_of_costs)
  long long sum_of_loss = 0;
  uint64_t expansions = 0;
  size_t explored = 0;
  std::vector<Config> plan;      // C^0 .. C^T when recorded
};

// Interleaved planning and execution with any RealtimePlanner.
RunResult run_realtime(RealtimePlanner& p, const Graph& g, const Config& starts, const Config& goals,
                       const RunOptions& opt);

// Full-horizon LaCAM: one search (until solved, exhausted or the timeout; then, with refine,
// LaCAM* until anytime_ms), then execution.
RunResult run_full_horizon(const Graph& g, const Config& starts, const Config& goals, LacamOptions lopt,
                           const RunOptions& opt, ActionPreference* pref = nullptr);

}  // namespace planner
