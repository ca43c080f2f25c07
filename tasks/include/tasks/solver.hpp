#pragma once
// The real-time planners of the lifelong comparison (planner/solver.hpp: pibt, naive,
// rtlacam, cspibt), set up for lifelong runs: a seed, kept PIBT priorities and a cap on
// the distance tables of goals no agent has any more. `refine`: RT-LaCAM*, LaCAM*
// refinement of the path to the epoch's goals (see planner/lacam.hpp).
#include <memory>
#include <string>

#include "planner/action_preference.hpp"
#include "planner/realtime_planner.hpp"

namespace tasks {

// pibt-rot (planner/rotation_pibt.hpp) plans LoRR rotation actions itself: the runner
// then executes its actions directly (no RotationExecutor); rotation action model only.
// wppl (planner/wppl.hpp): windowed LNS over pibt-rot's rollouts, the same contract.
constexpr const char* kRotationSolver = "pibt-rot";
// epibt (planner/epibt.hpp): EPIBT, PIBT with multi-action operations; rotation only too.
constexpr const char* kEpibtSolver = "epibt";
constexpr const char* kWpplSolver = "wppl";
inline bool is_rotation_native(const std::string& solver) { return solver == kRotationSolver || solver == kEpibtSolver || solver == kWpplSolver; }

// Throws std::invalid_argument for other names (lacam too), and for cspibt without `pref`.
std::unique_ptr<planner::RealtimePlanner> make_planner(const std::string& solver, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::GoalTest test, uint64_t seed,
                                                       planner::ActionPreference* pref = nullptr,
                                                       bool keep_priorities = true, bool refine = true);

}  // namespace tasks
