#pragma once
// ExpansionReserve: the part of a SUMO step's planner budget that distance-table growth and
// the detour searches around stuck AGVs leave to the search expansion that queries them.
// Both stop at the DistCache's deadline (dist_cache.hpp, immobile.hpp), but the expansion
// that meets the deadline goes on with lower bounds and still does its own work: with the
// deadline at the step's end, such a step costs the budget plus one expansion (measured on
// huge_warehouse_agv, 1000 AGVs, 1 ms: 1.3-2.0 ms per step in the ~10 steps after each stuck
// replan, while the detours were searched). So the tables' deadline is the step's minus one
// expansion's own work. Estimate: the dearest expansion of the last `window` steps that
// expanded (a step's search thread CPU over its expansions). Table work inflates it, so it
// errs on the safe side -- the cheapest one was tried first and left the post-replan steps
// at 1.1-1.4 ms: an expansion with detours active costs more than the plain ones before
// the replan. Capped at `max_share` of the budget, so the tables always grow by some (a
// search on lower bounds alone would stall).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace controller {

class ExpansionReserve {
 public:
  explicit ExpansionReserve(size_t window = 16, double max_share = 0.75);
  // One step's search: its thread CPU (ms) and its expansions (0: nothing to learn).
  void record(double search_cpu_ms, uint64_t expansions);
  // The reserve (ms) for a step with `budget_ms` left; 0 before any expansion was recorded.
  double ms(double budget_ms) const;

 private:
  size_t window_;
  double max_share_;
  std::vector<double> per_expansion_;  // ring of the last window_ steps' CPU per expansion
  size_t next_ = 0;
};

}  // namespace controller
