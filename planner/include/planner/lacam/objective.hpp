#pragma once
// Objective: the cost that LaCAM*'s refinement lowers (LacamOptions::objective).
//  - soc: the standard sum of costs (each agent charged up to its last arrival at its goal;
//    lacam3's get_sum_of_costs, Validator::sum_of_costs, what the papers report). An agent
//    parked on its goal is free only if it never leaves again: a plan that parks it early and
//    pushes it off later pays for all of the waiting.
//  - loss: the sum of loss (lacam3's get_sum_of_loss, Validator::sum_of_loss): a step on the
//    goal is free, whatever comes later. LaCAM*'s edge cost; Markov on configurations.
// The standard SOC of a path of configurations depends on its future (whether an agent leaves
// its goal again), so it is no edge cost: the tree's g stays the loss, and under soc the path
// the agents follow is kept apart and compared by its standard SOC (best_path.hpp).
#include <string>

namespace planner {

enum class Objective { soc, loss };

// "soc" | "loss" (the same names in the CLI and Python); throws std::invalid_argument.
Objective parse_objective(const std::string& s);
const char* objective_name(Objective o);

}  // namespace planner
