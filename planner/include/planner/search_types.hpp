#pragma once
// The vocabulary shared by every search and everything that drives one (RealtimePlanner,
// executors, the task layer), without the search itself (lacam.hpp).
#include <functional>

#include "planner/graph.hpp"

namespace planner {

enum class Status { Searching, Solved, NoSolution };
const char* to_string(Status s);  // "searching", "solved", "no_solution"

// Goal test on a configuration of num_agents() vertices. Empty: all agents at goals.
using GoalTest = std::function<bool(const Vertex* config)>;

}  // namespace planner
