#pragma once
// Readers for the MovingAI MAPF benchmark formats.
//  .map : "type octile", "height H", "width W", "map", then H rows of W characters.
//         '.', 'G', 'S', 'E' are free; '@', 'O', 'T', 'W' are blocked. 4-connected.
//  .scen: "version 1" then one agent per line, tab- or space-separated:
//         bucket map width height start_x start_y goal_x goal_y length
// Every malformed input throws InputError naming file:line.
#include <string>

#include "planner/graph.hpp"
#include "planner/instance.hpp"

namespace planner {

Graph load_map(const std::string& path);

// First `num_agents` agents of a scenario (all of them when num_agents < 0).
// Checks the instance (distinct starts/goals, cells free, goals reachable).
Instance load_scen(const std::string& path, const Graph& g, int num_agents);

}  // namespace planner
