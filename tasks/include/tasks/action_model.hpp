#pragma once
// Action models of the League of Robot Runners, as LoRR's logs spell them.
//
//   grid4    -- 4-connected moves, one cell per step (PlanViz's "MAPF": U D L R W)
//   rotation -- LoRR's "MAPF_T": state = cell + heading; F (forward one cell), R (turn
//               clockwise), C (turn counter-clockwise), W (wait); each takes one step and
//               a turn keeps the robot on its cell. All robots start facing east.
//
// Headings are LoRR's (planner/heading.hpp: the geometry, once). PlanViz's
// "MAPF" letters are its own (U = row + 1, D = row - 1, L = column - 1, R = column + 1):
// we write what PlanViz replays.
#include <string>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"
#include "planner/heading.hpp"

namespace tasks {

enum class ActionModel { Grid4, Rotation };

// "grid4" | "rotation"; throws std::invalid_argument otherwise.
ActionModel parse_action_model(const std::string& s);
std::string to_string(ActionModel m);
// The `actionModel` value of a LoRR log: "MAPF" (grid4) or "MAPF_T" (rotation).
std::string lorr_name(ActionModel m);

using planner::heading_of_move;
using planner::kHeadingLetter;
using planner::turn_toward;
// PlanViz "MAPF" letter of a grid4 move (W when u == v).
char grid4_letter(const planner::Graph& g, planner::Vertex u, planner::Vertex v);
// One executed MAPF_T step, checked as LoRR's ActionModelWithRotate applies it: robot i
// at pos[i] facing heading[i] does actions[i] (F: into the cell ahead, which must be free
// on the grid; R, C, W: stays); `next` must be the result. "" when it is, else the first
// problem. Vertex and swap conflicts are the Validator's (check_transition).
std::string check_rotation_step(const planner::Graph& g, const planner::Config& pos, const std::vector<int>& heading,
                                const std::string& actions, const planner::Config& next);

}  // namespace tasks
