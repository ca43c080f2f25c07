#pragma once
// Solver: the one factory. Every app and layer (bench, lifelong runs, the SUMO controller,
// the Python bindings, rtlacam-ggo) names a solver and builds it here, with all its options
// given at construction (SolverOptions), so no caller needs to know the concrete class.
//
// Cell solvers (planner_lacam: plan a configuration per step, any action model; an
// executor turns cell moves into robot actions):
//   pibt     -- PIBT alone, one step per iteration, no search (PibtPlanner)
//   lacam    -- full-horizon LaCAM: plan once, then execute (run_full_horizon; not real-time)
//   rtlacam  -- RT-LaCAM: one persistent, rerooted search (RtLacam); complete
//   naive    -- naive RT-LaCAM: a fresh LaCAM search every iteration (NaiveRtLacam)
//   cspibt   -- PIBT whose move order comes from a learned policy (CS-PIBT): needs `pref`
// Rotation solvers (planner_rotation: plan LoRR rotation actions F/R/C/W themselves, on
// (cell, heading) states; RotationPlanner; the rotation action model only):
//   pibt-rot -- causal PIBT over (cell, heading) (RotationPibt)
//   epibt    -- PIBT with multi-action operations (Epibt)
//   wppl     -- windowed LNS over pibt-rot's rollouts (Wppl)
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "planner/action_preference.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/realtime_planner.hpp"
#include "planner/rotation/epibt.hpp"
#include "planner/rotation/guidance.hpp"
#include "planner/rotation/wppl.hpp"

namespace planner {

enum class Solver { Pibt, Lacam, RtLacam, Naive, CsPibt, PibtRot, Epibt, Wppl };

// Every option of every solver; each solver reads its own part.
struct SolverOptions {
  uint64_t seed = 0;                 // every solver's tie-breaks (copied into lacam.seed, epibt.seed)
  // Cell solvers.
  LacamOptions lacam;                // pibt, rtlacam, naive, cspibt (PIBT's swap; RT-LaCAM*'s refine, ...)
  ActionPreference* pref = nullptr;  // PIBT's move order (cspibt: the learned policy, required)
  // Distance tables kept for goals no agent has any more (lifelong runs); 0: no cap.
  size_t max_dist_tables = 0;
  // pibt, rtlacam, naive, cspibt: distance tables shared from construction on (a planner
  // that replaces another on the same graph reuses its BFS work); null: tables of its own.
  std::shared_ptr<DistCache> dist_cache;
  // Rotation solvers.
  int heading = 0;                   // every robot's heading at the start (0 east .. 3 north; LoRR: east)
  std::vector<int> headings;         // one per robot instead of `heading` (RotationPlanner::set_headings)
  bool back_last = true;             // pibt-rot, wppl: RotationPibt::set_back_last
  bool pocket_exit = true;           // pibt-rot, wppl: RotationPibt::set_pocket_exit (epibt: epibt.pocket_exit)
  Guidance guidance;                 // distances in these costs (guidance.hpp); default: none
  EpibtOptions epibt;                // epibt: operation depth, revisits, LNS rounds, traffic flow
  WpplOptions wppl;                  // wppl: window, neighbourhood, ...
};

// Names, in kAll's order: "pibt | lacam | rtlacam | naive | cspibt | pibt-rot | epibt | wppl".
// realtime_only: without lacam; cell_only: without the rotation solvers.
std::string solver_names(bool realtime_only = false, bool cell_only = false);
std::vector<std::string> solver_list(bool realtime_only = false, bool cell_only = false);

// Throws std::invalid_argument "unknown solver 'x' (pibt | ...)" for other names.
Solver parse_solver(const std::string& name);
const char* to_string(Solver s);
inline bool needs_policy(Solver s) { return s == Solver::CsPibt; }
inline bool is_realtime(Solver s) { return s != Solver::Lacam; }
// LacamOptions::iter_refine unless set: on for full-horizon LaCAM* that refines before it
// executes (lacam, refine, anytime_ms > 0), where it is the stronger; off in real time, where
// it is even with LNS (docs/rt_lacam_star.md, session 45). rtlacam-bench and Python share it.
inline bool default_iter_refine(Solver s, bool refine, double anytime_ms)
{
  return refine && s == Solver::Lacam && anytime_ms > 0;
}
// LacamOptions::highways unless set: 1 (a move against a 1-wide corridor's grain ranks as
// two) for RT-LaCAM* (rtlacam, refine), where it lowers the executed standard SOC on
// warehouse-10-20-10-2-1 by 6 % (gm, 1 ms) to 15 % (0.01 ms) and changes nothing on maps
// without corridors; 0 for LaCAM and the paper's RT-LaCAM, which keep LaCAM's tree
// (bench_planner.py), and for full-horizon LaCAM*, where it was even (docs/rt_lacam_star.md,
// session 46). rtlacam-bench and Python share it.
inline int default_highways(Solver s, bool refine) { return refine && s == Solver::RtLacam ? 1 : 0; }
// Plans rotation actions itself (a RotationPlanner): needs the rotation action model.
inline bool plans_rotation(Solver s) { return s == Solver::PibtRot || s == Solver::Epibt || s == Solver::Wppl; }

// A real-time planner with its options applied. Throws std::invalid_argument for lacam (use
// run_full_horizon) and for cspibt without `opt.pref` ("solver cspibt needs a policy").
std::unique_ptr<RealtimePlanner> make_planner(Solver s, const Graph& g, const Config& starts, const Config& goals,
                                              const SolverOptions& opt = {}, GoalTest test = {});

}  // namespace planner
