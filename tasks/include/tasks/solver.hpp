#pragma once
// The three real-time planners of the lifelong comparison behind RealtimePlanner:
//   pibt    -- PIBT alone, one step per iteration (no search)
//   naive   -- naive RT-LaCAM: a fresh LaCAM search every iteration
//   rtlacam -- RT-LaCAM: one persistent search per progress epoch
#include <memory>
#include <string>

#include "planner/realtime_planner.hpp"

namespace tasks {

// Throws std::invalid_argument for other names.
std::unique_ptr<planner::RealtimePlanner> make_planner(const std::string& solver, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::GoalTest test, uint64_t seed);

}  // namespace tasks
