#pragma once
// The instance bound (issue 21): a lower bound on each AGV's time from its start to its
// goal that the instance alone fixes (net, vType, starts, goals, start headings), whatever
// the planner plans and however the executor drives. Every executor and every plan of one
// instance is measured against the same number: makespan / bound (bound.hpp's bound, every
// AGV alone on its *planned* path, moves with the plan and so with the execution).
//
// Physical (adg, adg-follow): an AGV alone on a shortest way, from rest to rest on its goal.
// Why it is a lower bound on any run, with anyone in the way or not:
// - whatever it drives is a walk of cells from its start to its goal, at least L metres long,
//   L the shortest walk between the cells' centres (Dijkstra; a lane between two centres is
//   never shorter than the straight line);
// - driving d metres from rest to rest takes at least rest_to_rest_s(d) (accel, max speed,
//   decel: the trapezoid is the fastest profile), and that function is concave with f(0) = 0,
//   so stopping on the way (waits, several stretches) never makes it faster than one
//   trapezoid over the whole walk: driving takes >= rest_to_rest_s(L);
// - no AGV drives a lane faster than its speed: the driving also takes >= C, the walk of
//   least time at each move's top speed (the faster of its two cells' fastest lanes, capped at
//   the vType's), so it takes >= max(rest_to_rest_s(L), C);
// - with headings (rotation solvers, fleet.turn_s) an AGV turns only at rest on its cell,
//   turn_s (rounded to SUMO steps as the Driver does) per quarter turn: add the fewest
//   quarter turns of any walk from its start heading to its goal (any heading there).
// Lock-step (a cell per tick): the fewest plan steps from start to goal, a move each (the
// BFS distance), plus, for the rotation solvers, the quarter turns (a turn is a step too):
// each step lasts >= 1 tick.
// The one-shot bound is the slowest AGV's; lifelong runs have tasks/free_flow.hpp instead
// (every AGV alone on shortest paths along its errand sequence).
#include <vector>

#include "controller/bound.hpp"
#include "gridify/cell_map.hpp"
#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace controller {

// Per agent, the fewest ticks in lockstep (above). `start_headings` empty: no turns.
std::vector<double> lockstep_alone_ticks(const planner::Graph& g, const planner::Config& starts, const planner::Config& goals,
                                         const std::vector<int>& start_headings = {});

// Per agent, the fewest seconds under physics (above). `cell_speed`: each cell's fastest lane
// (m/s; empty: none slower than k.max_speed). `start_headings` empty: no turns; else
// `turn_step_s` per quarter turn.
std::vector<double> physical_alone_s(const gridify::CellMap& map, const planner::Config& starts, const planner::Config& goals,
                                     const Kinematics& k, const std::vector<double>& cell_speed = {},
                                     const std::vector<int>& start_headings = {}, double turn_step_s = 0);

// Each cell's fastest lane (m/s), capped at top_speed: what bounds a move from above (lane
// costs take the slowest, lane_costs.hpp).
std::vector<double> fastest_cell_speeds(const gridify::CellMap& map, double top_speed);

}  // namespace controller
