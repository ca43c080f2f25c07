#pragma once
// FreeFlowBound: what a fleet could finish if nobody were in anyone's way (issue 20's
// free-flow bound). Every agent alone drives its own errand sequence -- its start, then the
// cell of each errand it finished, in order -- along shortest paths, and the bound is the
// time that takes:
//   bound errands/step = agents / (free-flow steps per finished errand)
// so throughput / bound is the share of the fleet's time that went into free-flow driving;
// what is lost is congestion, waiting for work (idle, queued, parked) and, in SUMO, physics
// beyond one trapezoid per errand.
//
// A shortest path of m moves costs `cost(m)` steps: m on the grid (one move per step, the
// default), or the vType's rest-to-rest time over m cells in SUMO (controller/bound.hpp).
// The rotation model's turns are not priced (a lower bound on its time, so the bound is
// optimistic there). Distances come from the shared DistCache, queried from the errand
// cells (stations: few tables); an errand cell the agent cannot reach costs nothing.
#include <functional>
#include <memory>
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

  long errands() const { return errands_; }
  double steps() const { return steps_; }    // free-flow steps of every finished errand
  double errands_per_step() const            // the bound; 0 before any errand
  {
    return steps_ > 0 ? static_cast<double>(last_.size()) * static_cast<double>(errands_) / steps_ : 0.0;
  }

 private:
  std::shared_ptr<planner::DistCache> cache_;
  Cost cost_;
  planner::Config last_;  // per agent: its start, then its last errand cell
  long errands_ = 0;
  double steps_ = 0;
};

}  // namespace tasks
