#pragma once
// The lifelong goal test of a progress epoch: "some agent that has not yet arrived stands
// on its goal". "Not yet arrived" is fixed when the epoch starts: agents that hold a task
// and do not already stand on its next errand cell. Requiring all agents at their goals
// would be infeasible with shared goals (two agents sent to one station) and pointless in
// a lifelong run, where the first completion changes the goals anyway.
//
// Battery urgency (urgency.hpp, battery_urgent): while an agent low on charge is pending,
// only the low ones count ("some low agent stands on its goal").
//
// When no agent is pending (all idle or already on their cells) every configuration
// passes: the planner may simply wait, and the completions at the end of the step start
// the next epoch.
#include <vector>

#include "planner/lacam/lacam.hpp"

namespace tasks {

class TaskManager;

planner::GoalTest lifelong_goal_test(const planner::Config& goals, const planner::Config& positions,
                                     const std::vector<char>& busy);

// The same for the task manager's current goals; with station queues or parking every
// agent off its goal is pending (TaskManager::awaited).
planner::GoalTest lifelong_goal_test(const TaskManager& tasks, const planner::Config& positions);

}  // namespace tasks
