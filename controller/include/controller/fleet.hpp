#pragma once
// Fleet: the MAPF instance of a run -- start and goal cell of every AGV -- from the
// config's explicit cells (vertex ids, station or junction ids) or random distinct cells
// drawn with a seed. Errors (cells off the graph, unknown names, two AGVs on one cell,
// more AGVs than cells) are ConfigErrors naming the key path.
#include <vector>

#include "controller/config.hpp"
#include "gridify/cell_map.hpp"
#include "planner/instance.hpp"

namespace controller {

// Lifelong runs: goals = starts (the task layer hands out the real goals).
planner::Instance make_instance(const Config& cfg, const gridify::CellMap& map);

// Random starts or goals (distinct cells) that one-at-a-time zones would refuse: each zone
// keeps the first of `cells` inside it, and every further one moves to the nearest cell
// (breadth-first along arcs) in no zone and not among `cells`, so a seed never draws an
// instance the rules refuse. Deterministic; a cell with nowhere to go stays (the rules' check
// then names it). Returns how many moved.
int keep_out_of_zones(const planner::Graph& g, const std::vector<std::vector<planner::Vertex>>& zones,
                      planner::Config& cells);

// One configured cell on the graph, or a ConfigError naming its key path.
planner::Vertex resolve_cell(const Config& cfg, const gridify::CellMap& map, const CellRef& c);

}  // namespace controller
