#pragma once
// One-way aisles on a grid map: the directed twin of a MovingAI warehouse (issue 24's
// "directed warehouse-10-20-10-2-1, alternate aisle directions"), for benchmarks and tests
// that compare one-way with two-way aisles on the same cells and instances.
//
// An aisle edge is a horizontal edge both of whose cells have a shelf (an obstacle that is
// not on the map's outer frame) directly above or below: the corridors between shelf rows.
// The rows that hold aisle edges are numbered top to bottom; row k's aisle edges point
// east when k is even and west when k is odd. Every other edge (open areas, the gaps between
// shelf blocks, the frame rows) stays two-way. The result keeps the grid view (attach_grid)
// so Manhattan bounds and grid tools still apply.
#include "planner/graph.hpp"

namespace planner {

// Throws std::invalid_argument if `grid` is not a grid graph, has no aisle edge, or the
// directed result is not strongly connected (an instance could then be unsolvable).
Graph one_way_aisles(const Graph& grid);

}  // namespace planner
