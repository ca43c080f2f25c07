#pragma once
// StepBudget: how a lifelong run spends one step's planning time (tasks/lifelong_run.hpp).
//
//   budget (per step)
//     - carry     the set_goals that started this step's epoch, run at the end of the last
//                 step: planning for this one, so it is charged here
//     - guard     how far table growth past a deadline overran it lately (a BFS chunk, a
//                 page fault): the step ends that much early
//     = left      for the precompute of prefetched tables (up to a share) and the search
//   reserve       one expansion's cost bound: an expansion cannot stop halfway, so the
//                 search starts another only while its bound fits before the deadline
//
// Cost bounds are CostEstimate's (mean + k deviations): `first` for a step's first
// expansion (at the root, on fresh tables: up to twice a later one), `later` for the rest,
// `overrun` for the guard. `bounded`: distance queries past a deadline answer lower bounds
// (dist_cache.hpp); only with a positive, finite time budget (for_budget). Without it
// (exact queries, or expansion-only budgets: deterministic runs) there is no guard.
#include <algorithm>
#include <cstdint>

#include "planner/budget.hpp"
#include "tasks/cost_estimate.hpp"

namespace tasks {

struct StepBudget {
  StepBudget(const planner::Budget& per_step, double deviations, double precompute_share, bool bound_queries)
      : per_step(per_step), deviations(deviations), precompute_share(precompute_share),
        bounded(bound_queries && per_step.ms > 0 && per_step.ms < 1e12)
  {
  }

  planner::Budget per_step;
  double deviations;        // k of the cost bounds
  double precompute_share;  // of a step's budget, at most, for the precompute first
  bool bounded;

  CostEstimate first, later, overrun;
  // The epoch start carried into the next step (0 without one): wall ms, thread CPU ms,
  // BFS vertices grown inside its distance queries.
  double carry_ms = 0, carry_cpu_ms = 0;
  uint64_t carry_pops = 0;

  double guard() const { return bounded ? overrun.bound(deviations) : 0.0; }
  double reserve() const { return first.bound(deviations); }
  // The step's budget once the epoch start and the guard are paid.
  planner::Budget left() const
  {
    planner::Budget b = per_step;
    b.ms = std::max(0.0, b.ms - carry_ms - guard());
    return b;
  }
  // The epoch start (at the end of a step) is the next step's planning: its table growth
  // stops at the precompute's share of that step's budget, less the first expansion.
  double epoch_start_ms() const { return std::max(0.0, precompute_share * per_step.ms - reserve()); }
  void carry(double ms, double cpu_ms, uint64_t pops) { carry_ms = ms, carry_cpu_ms = cpu_ms, carry_pops = pops; }
};

}  // namespace tasks
