#pragma once
// LaneGuidance: the low-dimensional guidance parameterisation that rtlacam-ggo searches.
//
// Why not GGO's per-edge weights: random-32-32-20 has ~3,300 directed arcs (x headings),
// and CMA-ES needs on the order of 10 x n evaluations to move n weights; one evaluation
// (a lifelong epibt run) costs seconds, so per-edge search does not fit an hour on two
// cores. Instead one log-multiplier per lane and direction, on top of the arrow field
// (planner/guidance.hpp arrow_guidance 1,3,1, its repair included):
//   row y:    east, west         (2 x height)
//   column x: south, north       (2 x width)
//   one for the quarter turn     (1)
// 2 (W + H) + 1 = 129 parameters on a 32 x 32 map. Each arc's cost is
//   clamp(round(unit x arrow cost x exp(p)), 1, kMaxCost),
// unit = 4 so that multipliers of ~0.9-1.1 already change a cost (integer costs, see
// Guidance). p = 0 is the arrow field itself, scaled by 4 (the same ranking: costs x k
// rank as costs x 1), so the search starts from today's default.
#include <Eigen/Dense>

#include "planner/graph.hpp"
#include "planner/rotation/guidance.hpp"

namespace ggo {

struct LaneGuidance {
  int width = 0, height = 0;
  int unit = 4;
  planner::Guidance base;  // arrow_guidance(g, 1, 3, 1)

  // Needs a grid graph (std::invalid_argument otherwise).
  explicit LaneGuidance(const planner::Graph& g, int unit = 4);

  int dims() const { return 2 * (width + height) + 1; }
  // The parameter of a forward move from cell (x, y) facing o (0 east, 1 south, 2 west, 3 north).
  int index(int x, int y, int o) const;
  int turn_index() const { return dims() - 1; }

  // Every forward cost and the turn in 1..Guidance::kMaxCost, whatever p (clamped).
  planner::Guidance to_guidance(const planner::Graph& g, const Eigen::VectorXd& p) const;
};

}  // namespace ggo
