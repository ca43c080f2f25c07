#pragma once
// Fleet: the MAPF instance of a run -- start and goal cell of every AGV -- from the
// config's explicit cells (vertex ids, station or junction ids) or random distinct cells
// drawn with a seed. Errors (cells off the graph, unknown names, two AGVs on one cell,
// more AGVs than cells) are ConfigErrors naming the key path.
#include "controller/config.hpp"
#include "gridify/cell_map.hpp"
#include "planner/instance.hpp"

namespace controller {

// Lifelong runs: goals = starts (the task layer hands out the real goals).
planner::Instance make_instance(const Config& cfg, const gridify::CellMap& map);

// One configured cell on the graph, or a ConfigError naming its key path.
planner::Vertex resolve_cell(const Config& cfg, const gridify::CellMap& map, const CellRef& c);

}  // namespace controller
