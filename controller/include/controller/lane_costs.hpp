#pragma once
// Lane costs: a slow lane's cells cost more in the planner's distance tables (the
// heuristics PIBT and LaCAM rank moves by; planner Graph::set_move_costs). The planner never
// sees SUMO: it gets one small integer per cell, the cost of a move onto it.
//
// A cell's speed is what an AGV may drive there: the slowest of its aisle's lanes (either
// direction: one cost per cell), capped at `top_speed` (the AGVs' own top speed: a lane
// faster than the AGVs is no faster for them). A junction cell takes its fastest lane: the
// move onto it drives on the lane it comes in on, and a slow aisle's own cells already carry
// its cost. cost = ceil(v_fast / v_cell), v_fast the fastest cell's speed: 1 on the fastest
// cells, ceil(1 / 0.4) = 3 on a lane at 40 % of it -- in lockstep the ticks the move takes
// (Commander::lane_ticks) when a cell per tick is the top speed. All cells equally fast:
// all 1, which leaves the planner's tables the plain BFS.
#include <cstdint>
#include <vector>

#include "gridify/cell_map.hpp"

namespace controller {

// The speed limit (m/s) an AGV keeps to on each cell, capped at top_speed (> 0).
std::vector<double> cell_speeds(const gridify::CellMap& map, double top_speed);

// Move costs per cell, as above (each in 1..255).
std::vector<uint8_t> lane_costs(const gridify::CellMap& map, double top_speed);

}  // namespace controller
