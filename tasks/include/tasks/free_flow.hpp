#pragma once
// FreeFlowBound: what a fleet could finish if nobody were in anyone's way (issue 20's
// free-flow bound). Every agent alone drives its own errand sequence -- its start, then the
// cell of each errand it finished, in order -- along shortest paths, and the bound is the
// time that takes:
//   bound errands/step = agents / (free-flow steps per errand)
// so throughput / bound says how close the fleet came to driving every errand alone; what
// is lost is congestion, waiting for work (idle, queued, parked) and, in SUMO, physics
// beyond one trapezoid per errand.
//
// Which errands price it: every errand the run handed out. Finished errands alone are a
// biased sample of a finite run -- short errands finish first -- so they price the fleet's
// errands too cheap, the more so the shorter the run and the slower the executor: a slower
// executor finishes fewer, shorter errands of the same task stream and got a higher bound
// than a faster one (the huge warehouse, 1000 AGVs, 1000 ticks: 10.03 errands/tick for
// adg-follow against 8.68 for lockstep, where physics makes each errand dearer). So at the
// end each agent's open errand (the one it holds, from its last errand cell) is priced whole
// too (errands_per_step(open)); an errand is in the sample because it was assigned, not because it was
// short enough to finish. errands_per_step() without them is the finished-only estimate.
//
// A shortest path of m moves costs `cost(m)` steps: m on the grid (one move per step, the
// default), or the vType's rest-to-rest time over m cells in SUMO (controller/bound.hpp).
// The rotation model's turns are not priced (a lower bound on its time, so the bound is
// optimistic there). Distances come from the shared DistCache, queried from the errand
// cells (stations: few tables); an errand cell the agent cannot reach costs nothing.
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_cache.hpp"

namespace tasks {

class FreeFlowBound {
 public:
  using Cost = std::function<double(int moves)>;  // steps for a shortest path of `moves` moves
  explicit FreeFlowBound(std::shared_ptr<planner::DistCache> cache, Cost cost = {})
      : cache_(std::move(cache)), cost_(std::move(cost)) {}

  void start(const planner::Config& positions) { last_ = positions; }
  // `agent` finished an errand on `cell`: it drove there alone from its last errand cell.
  void errand(int agent, planner::Vertex cell);

  long errands() const { return errands_; }  // finished
  double steps() const { return steps_; }    // free-flow steps of every finished errand
  // Free-flow steps of the open errands: `open[a]` is the cell of agent a's open errand, -1
  // for an agent that holds none.
  double open_steps(const planner::Config& open) const;
  // The bound over the finished errands and the open ones; 0 before any errand.
  double errands_per_step(const planner::Config& open) const
  {
    const auto [n, steps] = totals(open);
    return per_step(n, steps);
  }
  double errands_per_step() const { return per_step(errands_, steps_); }  // finished only
  // Free-flow steps per errand over the same errands; 0 without any.
  double steps_per_errand(const planner::Config& open) const
  {
    const auto [n, steps] = totals(open);
    return n > 0 ? steps / static_cast<double>(n) : 0.0;
  }

 private:
  std::pair<long, double> totals(const planner::Config& open) const;  // errands, steps: finished + open
  double per_step(long errands, double steps) const
  {
    return steps > 0 ? static_cast<double>(last_.size()) * static_cast<double>(errands) / steps : 0.0;
  }
  double price(planner::Vertex from, planner::Vertex to) const;  // cost of the shortest path, 0 if none

  std::shared_ptr<planner::DistCache> cache_;
  Cost cost_;
  planner::Config last_;  // per agent: its start, then its last errand cell
  long errands_ = 0;
  double steps_ = 0;
};

}  // namespace tasks
