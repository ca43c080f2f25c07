#pragma once
// Stub mouths: the cells where stations' dead-end stubs join the net, and a routing cost on
// them (issue 24: K on large_oneway_lifelong over long runs).
//
// Traced on large_oneway_lifelong (s34-24c, 500-1000 ticks): every stall >= 100 ticks was a
// loaded AGV held in head-on traffic on the two-way cross aisle that runs past the drop
// stations' stubs. The distance tables made that aisle as short as the middle one, so loaded
// AGVs travelled far along it, past every other station's mouth, where the AGVs entering and
// leaving those stations cross them. A move onto a mouth cell costing `cost` more moves in the
// distance tables (Graph::set_move_costs: only the heuristics PIBT, LaCAM and the assigners
// rank by change, not the search space, so no guarantee does) makes through traffic use the
// aisles without stations. Every path into a stub enters its mouth, so an AGV bound for that
// station pays the cost on every route alike: only passing a station it is not bound for
// counts against a route.
#include <cstdint>
#include <vector>

#include "planner/graph.hpp"

namespace tasks {

// The mouths (one per station whose cell is in a dead-end corridor, battery.hpp
// dead_end_corridor), each once, in the order of `stations`.
std::vector<planner::Vertex> stub_mouths(const planner::Graph& g, const std::vector<planner::Vertex>& stations);

// g's move costs (all 1 when it has none) with `cost` added on every mouth of `stations`
// (capped at 255). cost 0: g's costs unchanged.
std::vector<uint8_t> mouth_costs(const planner::Graph& g, const std::vector<planner::Vertex>& stations, int cost);

}  // namespace tasks
