#pragma once
// RotationSettings: the rotation solvers' options (pibt-rot, epibt, wppl) by the names of the
// SUMO YAML's planner.rotation keys (controller/README.md), and the rules every front end
// shares: which solver reads which key, each key's range, and rtlacam-lifelong's defaults per
// solver. Python's rotation= dict (python/src/module.cpp) fills one key by key;
// rtlacam-lifelong (apps/lifelong_cli.hpp SolverCli) takes its per-solver defaults from here,
// so a Python run and a CLI run with the same options are the same run.
#include <array>
#include <string>
#include <vector>

#include "planner/solver.hpp"

namespace planner {

struct RotationSettings {
  // A value-initialised one is the planners' own defaults (SolverOptions, EpibtOptions,
  // WpplOptions: the papers' rules, no guidance, no traffic flow).
  bool back_last = SolverOptions{}.back_last;        // pibt-rot, wppl
  std::string guidance = "none";                     // none | arrows (rotation/guidance.hpp)
  std::array<int, 3> guidance_costs = {1, 3, 1};     // arrows: along, against, turn (1..Guidance::kMaxCost)
  bool traffic_flow = EpibtOptions{}.tf.on;          // epibt
  int depth = EpibtOptions{}.depth;                  // epibt: 3..5
  int lns_rounds = EpibtOptions{}.lns_rounds;        // epibt: -1..1000000 (-1: until the deadline)
  int revisit = EpibtOptions{}.revisit;              // epibt: 1..1000000
  std::string priority = "distance";                 // epibt: distance | age
  bool pocket_exit = SolverOptions{}.pocket_exit;    // every rotation solver
  bool leavers_first = EpibtOptions{}.leavers_first; // epibt
  int window = WpplOptions{}.window;                  // wppl: 1..1000
  int neighbourhood = WpplOptions{}.neighbourhood;   // wppl: 1..100000

  // rtlacam-lifelong's defaults for `kind` (measured on LoRR maps; the SUMO YAML's differ,
  // controller/src/config.cpp): arrows guidance for pibt-rot and epibt (+8 to +20 % errands
  // per step for pibt-rot on MR23 and RANDOM-01..05), none for wppl (arrows cost 5 % on
  // MR23-I-04); traffic flow for epibt (+2 to +69 % on MR23; Epibt keeps it off where its
  // tables would not fit). docs/rotation_lorr.md "Guidance graph", "Traffic flow".
  static RotationSettings lifelong(Solver kind);
};

// planner.rotation's keys, in the README's order.
const std::vector<std::string>& rotation_keys();

// "" when `kind` reads `key`, else why not ("only with solver wppl, not epibt"). Throws
// std::invalid_argument for a key not in rotation_keys().
std::string rotation_key_misuse(Solver kind, const std::string& key);

// The first value out of its range or choice set, as "key: why" ("depth: must be in 3..5,
// got 7"); "" if none. guidance_costs count only with guidance arrows.
std::string check(const RotationSettings& s);

// `s` into `so` (the fields each rotation solver reads; arrows guidance built on `g`).
// Throws std::invalid_argument where check(s) fails or arrows need a grid.
void apply(const RotationSettings& s, const Graph& g, SolverOptions& so);

}  // namespace planner
