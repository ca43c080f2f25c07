#pragma once
// The three real-time planners of the lifelong comparison behind RealtimePlanner:
//   pibt    -- PIBT alone, one step per iteration (no search)
//   naive   -- naive RT-LaCAM: a fresh LaCAM search every iteration
//   rtlacam -- RT-LaCAM: one persistent search per progress epoch (`refine`: RT-LaCAM*,
//              LaCAM* refinement of the path to the epoch's goals; see planner/lacam.hpp)
//   cspibt  -- PIBT whose move order comes from `pref` (a learned policy): CS-PIBT
// `pref` (optional for the others) orders PIBT's moves inside any of them.
#include <memory>
#include <string>

#include "planner/realtime_planner.hpp"

namespace tasks {

// Throws std::invalid_argument for other names, and for cspibt without `pref`.
std::unique_ptr<planner::RealtimePlanner> make_planner(const std::string& solver, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::GoalTest test, uint64_t seed,
                                                       planner::ActionPreference* pref = nullptr,
                                                       bool keep_priorities = true, bool refine = true);

}  // namespace tasks
