#pragma once
// StepBudget: how a step's planning time is spent, in both lifelong back ends: the grid's
// LifelongRun (tasks/lifelong_run.hpp: one LoRR step) and the SUMO controller's Run::step
// (controller/src/run.cpp: one SUMO step). One object, so the two spend a step alike.
//
//   budget (per step)
//     - carry     work charged to this step before its search: the epoch start (set_goals,
//                 run at the end of the last step), and in SUMO also the commits, a stuck
//                 replan or a rules restart since the last step's search. It is planning for
//                 this step, so it is charged here; charge() adds (SUMO charges several
//                 pieces between two searches), paid() clears once the step counted it
//     - guard     how far table growth past a deadline overran it lately (a BFS chunk, a
//                 page fault): the step ends that much early
//     = left      for the precompute of prefetched tables (up to a share) and the search
//   reserve       one expansion's cost bound: an expansion cannot stop halfway, so table
//                 growth (and the search) stops that much before the deadline. Capped at
//                 reserve_cap of the time left where a back end needs the tables to grow by
//                 some in every step (SUMO: a search on lower bounds alone would stall).
//                 With reserve_window (SUMO) the dearest expansion of the last searches
//                 instead of the cost bound: after a stuck replan the expansions that also
//                 search detours stay dear for ~10 steps, and a bound that follows the mean
//                 forgets a spike within ~4 samples (measured: the mean + 4 deviations bound
//                 in Run::step raised large_warehouse_agv's max planner CPU per SUMO step at
//                 1 ms, new / old median 1.37 over 4 interleaved pairs)
//   skip          a step whose carry left nothing runs no search at all, where the search
//                 would still make its one forced expansion (0.7-2 ms at 1000 agents); with
//                 skip_late (the grid's --skip-late-search) instead one left less than an
//                 expansion's bound, where a step without carry has room for one. At most
//                 max_skips in a row: the search progresses
//
// Clock: the grid's budget is the wall clock's (LoRR's step); the controller's bounds the
// planner thread's CPU (planner.budget_ms, metrics.json planner_cpu_ms_per_step), so its
// carry is counted in CPU ms (`cpu_clock`).
//
// Cost bounds are CostEstimate's (mean + k deviations): `first` for a step's first
// expansion (at the root, on fresh tables: up to twice a later one; the controller's search
// is one call per step, so it learns `first` from the call's mean expansion, at 1000 agents
// and 1 ms mostly its only one), `later` for the rest (grid), `overrun` for the guard.
// `bounded`: distance queries past a deadline answer lower bounds (dist_cache.hpp); only
// with a positive, finite time budget (timed). Without it (exact queries, or expansion-only
// budgets: deterministic runs) there is no guard; without a time budget the controller
// neither skips nor moves a deadline, and left() stays unlimited.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "planner/budget.hpp"
#include "tasks/cost_estimate.hpp"

namespace tasks {

struct StepBudget {
  StepBudget(const planner::Budget& per_step, double deviations, double precompute_share, bool bound_queries)
      : per_step(per_step), deviations(deviations), precompute_share(precompute_share),
        bounded(bound_queries && timed(per_step))
  {
  }

  planner::Budget per_step;
  double deviations;        // k of the cost bounds
  double precompute_share;  // of a step's budget, at most, for the precompute first
  bool bounded;
  bool cpu_clock = false;   // the carry counts in thread CPU ms (controller), else wall ms (grid)
  double reserve_cap = 0;   // reserve() at most this share of the time left; 0: uncapped
  int max_skips = 3;        // searches skipped in a row at most
  size_t reserve_window = 0;  // > 0: reserve() is the dearest of the last this many searches' expansions
  bool skip_late = false;   // skip(): where less than one expansion's bound is left (else: nothing)

  CostEstimate first, later, overrun;
  // Work charged to the next step's search (0 without any): wall ms, thread CPU ms, BFS
  // vertices grown inside its distance queries.
  double carry_ms = 0, carry_cpu_ms = 0;
  uint64_t carry_pops = 0;
  int skipped = 0;              // searches skipped in a row
  long searches_skipped = 0;    // over the run
  std::vector<double> recent;   // reserve_window: ring of the last searches' ms per expansion
  size_t recent_next = 0;

  static bool timed(const planner::Budget& b) { return b.ms > 0 && b.ms < 1e12; }

  double guard() const { return bounded ? overrun.bound(deviations) : 0.0; }
  // One expansion's cost bound (or the dearest recent one), capped at reserve_cap of
  // `left_ms` (the step's time left).
  double reserve(double left_ms) const
  {
    const double r = reserve_window == 0 ? first.bound(deviations)
                     : recent.empty()    ? 0.0
                                         : *std::max_element(recent.begin(), recent.end());
    return reserve_cap > 0 ? std::min(r, reserve_cap * std::max(0.0, left_ms)) : r;
  }
  double reserve() const { return reserve(per_step.ms); }
  // A step's budget `b` (per_step, or a tick's for a rotation solver in SUMO) once the carry
  // and the guard are paid.
  planner::Budget left(planner::Budget b) const
  {
    b.ms = std::max(0.0, b.ms - (cpu_clock ? carry_cpu_ms : carry_ms) - guard());
    return b;
  }
  planner::Budget left() const { return left(per_step); }
  // Distance tables (and the controller's detours around stuck AGVs) stop growing this long
  // after the search starts with `left_ms`: the expansion that meets their deadline still
  // has its own work to do.
  double tables_ms(double left_ms) const { return std::max(0.0, left_ms - reserve(left_ms)); }
  // The precompute of prefetched tables before the search, with `left_ms` left: up to its
  // share, leaving room for the one expansion the search always makes; it overruns its
  // deadline too (guard). <= 0: none.
  double precompute_ms(double left_ms) const
  {
    return std::min(precompute_share * left_ms, left_ms - reserve(left_ms)) - guard();
  }
  // The grid's epoch start (at the end of a step) is the next step's planning: its table
  // growth stops at the precompute's share of that step's budget, less the first expansion.
  double epoch_start_ms() const { return std::max(0.0, precompute_share * per_step.ms - reserve()); }

  // Work charged to the next search; paid() once a step has counted it.
  void charge(double ms, double cpu_ms, uint64_t pops = 0) { carry_ms += ms, carry_cpu_ms += cpu_ms, carry_pops += pops; }
  void paid() { carry_ms = 0, carry_cpu_ms = 0, carry_pops = 0; }
  // The time of a search that made `expansions` (0: nothing to learn).
  void expanded(double cpu_ms, uint64_t expansions)
  {
    if (expansions == 0 || !(cpu_ms >= 0)) return;
    const double c = cpu_ms / static_cast<double>(expansions);
    first.add(c);
    if (reserve_window == 0) return;
    if (recent.size() < reserve_window) {
      recent.push_back(c);
    } else {
      recent[recent_next] = c;
      recent_next = (recent_next + 1) % reserve_window;
    }
  }

  // Whether a step that would search, with `budget_ms` its budget and `left_ms` left after
  // the carry, skips its search (`may`: the back end allows it). No room means nothing left
  // (the controller: its carry is commits, replans and epoch starts of 1000 AGVs, which may
  // exceed the step whatever an expansion costs), or with skip_late less than one
  // expansion's bound where a step without carry has room for one (else skipping gains
  // nothing: every step overruns). Counts the skip; a search resets the count in a row.
  bool skip(bool may, double budget_ms, double left_ms)
  {
    const double r = first.bound(deviations);
    const bool room = skip_late ? !(first.known() && left_ms < r && budget_ms >= r) : left_ms > 0;
    const bool s = may && skipped < max_skips && !room;
    skipped = s ? skipped + 1 : 0;
    searches_skipped += s;
    return s;
  }
};

}  // namespace tasks
