#pragma once
// Solver: the one place that maps a solver name to a planner. Every app and layer (bench,
// lifelong runs, the SUMO controller, the Python bindings) parses and builds through it.
//   pibt    -- PIBT alone, one step per iteration, no search (PibtPlanner)
//   lacam   -- full-horizon LaCAM: plan once, then execute (run_full_horizon; not real-time)
//   rtlacam -- RT-LaCAM: one persistent, rerooted search (RtLacam)
//   naive   -- naive RT-LaCAM: a fresh LaCAM search every iteration (NaiveRtLacam)
//   cspibt  -- PIBT whose move order comes from a learned policy (CS-PIBT): needs `pref`
// `pref` (optional for all but cspibt) orders PIBT's moves inside any of them.
#include <memory>
#include <string>
#include <vector>

#include "planner/action_preference.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/realtime_planner.hpp"

namespace planner {

enum class Solver { Pibt, Lacam, RtLacam, Naive, CsPibt };

// "pibt | lacam | rtlacam | naive | cspibt" (realtime_only: without lacam).
std::string solver_names(bool realtime_only = false);
std::vector<std::string> solver_list(bool realtime_only = false);

// Throws std::invalid_argument "unknown solver 'x' (pibt | ...)" for other names.
Solver parse_solver(const std::string& name);
const char* to_string(Solver s);
inline bool needs_policy(Solver s) { return s == Solver::CsPibt; }
inline bool is_realtime(Solver s) { return s != Solver::Lacam; }

// A real-time planner. Throws std::invalid_argument for lacam (use run_full_horizon) and
// for cspibt without `pref` ("solver cspibt needs a policy").
std::unique_ptr<RealtimePlanner> make_planner(Solver s, const Graph& g, const Config& starts, const Config& goals,
                                              const LacamOptions& opt = {}, ActionPreference* pref = nullptr,
                                              GoalTest test = {});

}  // namespace planner
