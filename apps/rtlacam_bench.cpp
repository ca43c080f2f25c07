// rtlacam-bench: the RT-LaCAM paper's experiment on one MovingAI instance.
// Prints one JSON object per run; --out writes the executed plan (LaCAM result format).
// --policy plugs a learned one-step policy into PIBT's move order (policy/README.md);
// solver cspibt is that policy with PIBT's collision shield and no search.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "planner/output_file.hpp"
#include "cli.hpp"
#include "planner/error.hpp"
#include "planner/movingai.hpp"
#include "planner/one_way_aisles.hpp"
#include "planner/plan_io.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/lacam/runner.hpp"
#include "planner/solver.hpp"
#include "planner/validator.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"
#include "executor/rotation_execution.hpp"

using namespace planner;

int main(int argc, char** argv)
{
  CLI::App app{"RT-LaCAM benchmark: interleaved planning and execution on a MovingAI instance"};
  std::string map_file, scen_file, solver = "rtlacam", out_file, policy_file, action_model = "grid4";
  int agents = 0;
  double cutoff_ms = 1.0, timeout_s = 60.0;
  uint64_t budget_expansions = 0, seed = 0;
  long long max_steps = 100000;
  bool compact = false, no_swap = false, refine = true, one_way = false;
  double anytime_ms = 0, restart_rate = LacamOptions{}.restart_rate;
  bool lns = true;
  int lns_window = LacamOptions{}.lns_window;
  int lns_agents = LacamOptions{}.lns_agents;
  std::string lns_nbh = "random", objective = "soc";
  bool scatter = true, dive = LacamOptions{}.dive, scatter_first = false;  // scatter: measured, docs/rt_lacam_star.md
  bool scatter_live = LacamOptions{}.scatter_live, scatter_live_keep = LacamOptions{}.scatter_live_keep;
  double scatter_live_share = LacamOptions{}.scatter_live_share;
  int scatter_margin = LacamOptions{}.scatter_margin, scatter_lead = LacamOptions{}.scatter_lead,
      scatter_max_passes = 0, scatter_dive_passes = LacamOptions{}.scatter_dive_passes;
  double cold_factor = LacamOptions{}.cold_factor;
  bool scatter_dive_guard = LacamOptions{}.scatter_dive_guard, reprice = LacamOptions{}.reprice, lookahead = LacamOptions{}.lookahead,
       scatter_lead_dive = LacamOptions{}.scatter_lead_dive, scatter_prepare = LacamOptions{}.scatter_prepare,
       guided_cost = LacamOptions{}.guided_cost, dive_pause = LacamOptions{}.dive_pause,
       cold_end = LacamOptions{}.cold_end, scatter_lead_guided = LacamOptions{}.scatter_lead_guided;
  app.add_option("--map", map_file, "MovingAI .map file")->required();
  app.add_option("--scen", scen_file, "MovingAI .scen file (first N agents are used)")->required();
  app.add_option("--agents,-N", agents, "number of agents")->required()->check(cli::positive());
  app.add_option("--solver", solver, solver_names(false, true) + " (cspibt: pibt ordered by --policy)")
      ->check(CLI::IsMember(solver_list(false, true)))
      ->capture_default_str();
  auto* cutoff_opt = app.add_option("--cutoff-ms", cutoff_ms,
                                    "planning budget per iteration (wall clock); with --budget-expansions only when "
                                    "given too")
                         ->check(cli::finite_range(0, 3.6e6))
                         ->capture_default_str();
  app.add_option("--budget-expansions", budget_expansions,
                 "planning budget per iteration in LaCAM expansions, alone (deterministic runs) unless --cutoff-ms is "
                 "given too (then whichever ends first); 0 = none");
  app.add_option("--timeout-s", timeout_s, "limit on the cumulative planning time")
      ->check(cli::finite_range(0, 1e7))
      ->capture_default_str();
  app.add_option("--max-steps", max_steps, "limit on executed steps (iterative solvers)")
      ->check(cli::non_negative())
      ->capture_default_str();
  app.add_option("--seed", seed, "random seed")->capture_default_str();
  app.add_flag("--no-swap", no_swap, "PIBT without the swap operation (paper-faithful vanilla LaCAM)");
  bool free_first = false;
  auto* free_first_opt = app.add_flag("--free-first,!--no-free-first", free_first,
                                      "PIBT ties between equally short moves toward the goal: free vertices first "
                                      "(pibt.hpp); default: on for --solver rtlacam with --refine (RT-LaCAM*), else off");
  int highways = 0, highway_min_run = LacamOptions{}.highway_min_run;
  auto* highways_opt = app.add_option("--highways", highways,
                                      "PIBT ranks moves by distances where a move against a 1-wide corridor's grain costs "
                                      "this much more (highways.hpp); 0 = off; default: 1 for --solver rtlacam with "
                                      "--refine (RT-LaCAM*), else 0")
                           ->check(CLI::Range(0, 200));
  app.add_option("--highway-min-run", highway_min_run, "highways: least corridor run (cells) that gets a grain")
      ->check(cli::positive())
      ->capture_default_str();
  bool reserve = true;
  app.add_flag("--reserve,!--no-reserve", reserve,
               "keep the cutoff before the first solution too: an expansion after the first of an iteration starts "
               "only while the costliest one so far fits (--no-reserve: the paper's loop, which starts one until the "
               "cutoff)");
  int mc_rollouts = LacamOptions{}.mc_rollouts;
  app.add_option("--mc-rollouts", mc_rollouts,
                 "Monte-Carlo generation: PIBT rollouts per expansion, the least edge cost + h kept (lacam.hpp)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  bool mc_first = LacamOptions{}.mc_first;
  app.add_flag("--mc-first,!--no-mc-first", mc_first,
               "Monte-Carlo generation in the search for the first solution (lacam3)");
  bool mc_refine = LacamOptions{}.mc_refine;
  app.add_flag("--mc-refine,!--no-mc-refine", mc_refine, "Monte-Carlo generation in refinement's expansions (lacam3)");
  int lg_window = LacamOptions{}.lg_window;
  app.add_option("--local-guidance", lg_window,
                 "local guidance (LG-LaCAM): window of each agent's space-time path that PIBT's first choice follows "
                 "(local_guidance.hpp); 0 = off")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  int lg_weight = LacamOptions{}.lg_collision_weight;
  app.add_option("--lg-collision-weight", lg_weight,
                 "local guidance: 0 = collisions first, then cost; K = a collision costs K steps")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  bool lg_rest = LacamOptions{}.lg_rest;
  app.add_flag("--lg-rest,!--no-lg-rest", lg_rest, "local guidance: an agent on its goal is guided to stay");
  bool lg_first = LacamOptions{}.lg_first;
  app.add_flag("--lg-first,!--no-lg-first", lg_first, "local guidance in the search for the first solution");
  int lg_window_unpaused = 0;
  app.add_option("--lg-window-unpaused", lg_window_unpaused,
                     "local guidance window in the first search when --cutoff-ms is below --pause-min-ms (every iteration "
                     "one expansion); 0 = off (default: it costs each iteration ~4x; " + std::to_string(LacamOptions::kStarLgWindowUnpaused) + " measured, docs/rt_lacam_star.md)")
          ->check(CLI::Range(0, 64));
  int lg_refresh = LacamOptions{}.lg_refresh;
  app.add_option("--lg-refresh", lg_refresh,
                 "amortized local guidance: keep each agent's windowed path while it is followed and plan it again "
                 "after R rounds (or when it is not followed); 0 = every agent every round (local_guidance.hpp)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  double lg_budget = LacamOptions{}.lg_budget;
  app.add_option("--lg-budget", lg_budget,
                 "local guidance: at most about K A* nodes per agent per round (a full round at window 5 pushes ~30); "
                 "0 = no cap")
      ->check(cli::finite_range(0, 1e6))
      ->capture_default_str();
  bool lg_repair = LacamOptions{}.lg_repair;
  app.add_flag("--lg-repair,!--no-lg-repair", lg_repair,
               "amortized local guidance: a kept path that meets a path planned before it is planned again");
  double lg_gate = LacamOptions{}.lg_gate;
  app.add_option("--lg-gate", lg_gate,
                 "local guidance in the first search only if at least this share of the first N windowed paths are "
                 "slowed by other agents (congestion at the start); 0 = always")
      ->check(cli::finite_range(0, 1))
      ->capture_default_str();
  bool lg_refine = LacamOptions{}.lg_refine;
  app.add_flag("--lg-refine,!--no-lg-refine", lg_refine, "local guidance in refinement's expansions");
  bool resumable = LacamOptions{}.resumable;
  app.add_flag("--resumable,!--no-resumable", resumable,
               "a LaCAM expansion may stop at the cutoff and go on in the next iteration, the agents waiting meanwhile "
               "(lacam.hpp; the tree is the same); --no-resumable: one expansion always ends in its iteration")
      ->capture_default_str();
  double pause_min_ms = LacamOptions{}.pause_min_ms;
  app.add_option("--pause-min-ms", pause_min_ms,
                 "below this cutoff an expansion always ends in its iteration (the paper's loop), so the agents do not "
                 "wait for it; 0: resumable at any cutoff")
      ->check(cli::non_negative())
      ->capture_default_str();
  app.add_flag("--refine,!--no-refine", refine,
               "LaCAM* refinement after the first solution (RT-LaCAM*); --no-refine: the paper's RT-LaCAM")
      ->capture_default_str();
  app.add_option("--objective", objective,
                 "what refinement lowers: soc (standard sum of costs, each agent up to its last arrival) or loss "
                 "(sum of loss; objective.hpp)")
      ->capture_default_str()
      ->check(CLI::IsMember({"soc", "loss"}));
  app.add_flag("--lns,!--no-lns", lns, "with --refine: LNS steps on the best path (lns_refiner.hpp)")
      ->capture_default_str();
  app.add_option("--lns-agents", lns_agents, "agents replanned per LNS step")->capture_default_str()->check(cli::positive());
  app.add_option("--lns-neighbourhood", lns_nbh, "agents an LNS step replans (lns_refiner.hpp)")
      ->capture_default_str()
      ->check(CLI::IsMember({"random", "blocking", "intersection", "adaptive"}));
  // Bounded: the LNS occupancy table is (window + 1) x |V| cells (checked on the map below).
  auto* lns_window_opt = app.add_option("--lns-window", lns_window, "time steps replanned per LNS step")
                             ->capture_default_str()
                             ->check(CLI::Range(1, 1000000));
  std::string trace_best;
  app.add_option("--trace-best", trace_best,
                 "rtlacam: write per iteration 'iteration predicted_soc' here: the standard SOC of the executed moves "
                 "followed by the path the planner follows now (-1 before a solution); diagnostics, slows the run");
  int refine_threads = 0;
  app.add_option("--refine-threads", refine_threads,
                 "with --refine and --objective soc: refiner threads running LNS on copies of the followed path "
                 "(refine_thread.hpp); 0 = none, the search makes its own LNS steps")
      ->capture_default_str()
      ->check(CLI::Range(0, 64));
  bool iter_refine = false;
  auto* iter_refine_opt = app.add_flag(
      "--iter-refine,!--no-iter-refine", iter_refine,
      "with --refine and --objective soc: iterative refinement (lacam3's refiner: groups of agents replanned by SIPP "
      "over the rest of the horizon, iter_refiner.hpp) in place of the search's LNS steps, or in the refiner threads' "
      "(--refine-threads); default: on for --solver lacam with --anytime-ms (LaCAM* planned before moving), else off");
  app.add_flag("--scatter,!--no-scatter", scatter,
               "with --refine: space-utilisation optimisation guiding PIBT after the first solution (scatter.hpp)")
      ->capture_default_str();
  // Counts and lengths: a negative one was taken silently.
  app.add_option("--scatter-margin", scatter_margin, "SUO: extra path length allowed per agent")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_option("--scatter-lead", scatter_lead, "SUO starts this many steps ahead on the best path")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_option("--scatter-max-passes", scatter_max_passes, "SUO passes at most (0: until collisions stop dropping)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_option("--scatter-dive-passes", scatter_dive_passes, "SUO passes before the first guided dive")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_flag("--dive,!--no-dive", dive, "with --refine: PIBT rollouts from the root, inserted and rewired")
      ->capture_default_str();
  app.add_flag("--lookahead,!--no-lookahead", lookahead,
               "with --refine on a directed graph: a lookahead search from k steps on while refinement is over (rt_lacam.hpp)")
      ->capture_default_str();
  app.add_flag("--scatter-dive-guard,!--no-scatter-dive-guard", scatter_dive_guard,
               "a guided dive goes on by distances once as long as the rest of the best path (lacam.hpp)");
  app.add_flag("--scatter-lead-dive,!--no-scatter-lead-dive", scatter_lead_dive,
               "SUO's lead check also counts the guided dive after its passes (lacam.hpp)");
  app.add_flag("--scatter-prepare,!--no-scatter-prepare", scatter_prepare,
               "timed: SUO's per-vertex lists are built in slices before its first start (lacam.hpp)");
  app.add_flag("--guided-cost,!--no-guided-cost", guided_cost,
               "timed: refinement expansions guided by SUO's paths have their own learnt cost (lacam.hpp)");
  app.add_flag("--dive-pause,!--no-dive-pause", dive_pause,
               "timed: a dive step's PIBT call stops at the deadline and goes on in the next call (lacam.hpp)");
  app.add_flag("--cold-end,!--no-cold-end", cold_end,
               "timed: the step after a cache sweep (an SUO slice or paused dive step at its deadline, an LNS step or page mapping) is priced at --cold-factor x its rate (lacam.hpp)");
  app.add_flag("--scatter-lead-guided,!--no-scatter-lead-guided", scatter_lead_guided,
               "timed: SUO's lead check prices a guided dive step at the guided step's cost (lacam.hpp)");
  app.add_option("--cold-factor", cold_factor, "with --cold-end: the step after a cache sweep is priced at this x its rate")
      ->check(cli::finite_range(1, 100))
      ->capture_default_str();
  app.add_flag("--reprice,!--no-reprice", reprice,
               "soc: price a goal path again when the agents' move cut its pricing short (lacam.hpp)");
  app.add_flag("--scatter-first", scatter_first, "SUO before the first solution (changes LaCAM's tree)");
  app.add_flag("--scatter-live,!--no-scatter-live", scatter_live,
               "with --refine: SUO from the start shares the calls before the first solution, each agent's path "
               "guiding PIBT as soon as it is planned (changes LaCAM's tree; lacam.hpp)")
      ->capture_default_str();
  app.add_option("--scatter-live-share", scatter_live_share, "with --scatter-live: SUO's share of each call before the first solution")
      ->check(cli::finite_range(0, 1))
      ->capture_default_str();
  app.add_flag("--scatter-live-keep,!--no-scatter-live-keep", scatter_live_keep,
               "with --scatter-live: refinement goes on with that SUO (dive from the root) instead of a fresh one ahead")
      ->capture_default_str();
  app.add_option("--restart-rate", restart_rate, "LaCAM*: probability that a revisit pushes the root instead")
      ->check(cli::finite_range(0, 1))
      ->capture_default_str();
  app.add_option("--anytime-ms", anytime_ms,
                 "solver lacam with refine: keep refining until this much planning time in all (refine-after-solve)")
      ->check(cli::finite_range(0, 1e10))
      ->capture_default_str();
  app.add_option("--out", out_file, "write the executed plan here (LaCAM result format)");
  app.add_flag("--json", compact, "print the result as one compact JSON line");
  app.add_option("--policy", policy_file, "learned policy weights: PIBT tries moves in its order (CS-PIBT)");
  app.add_option("--action-model", action_model,
                 "grid4 | rotation (LoRR MAPF_T: the executed cell plan is run with headings; adds rotation_* fields)")
      ->check(CLI::IsMember({"grid4", "rotation"}))
      ->capture_default_str();
  double progress_s = 2;
  app.add_flag("--one-way-aisles", one_way,
               "make the aisles between shelf rows one-way, alternately east and west (one_way_aisles.hpp)");
  app.add_option("--progress-s", progress_s, "seconds between progress lines on stderr; 0 = none")->capture_default_str();
  cli::add_version(app, "rtlacam-bench");
  RTLACAM_PARSE(app, argc, argv);
  if (needs_policy(parse_solver(solver)) && policy_file.empty()) {
    std::cerr << "rtlacam-bench: --solver cspibt needs --policy WEIGHTS" << std::endl;
    return cli::kBadInput;
  }

  try {
    // The same cells with one-way aisles (planner/one_way_aisles.hpp), or the map as it is.
    const Graph g = [&] {
      if (!one_way) return load_map(map_file);
      try {
        return one_way_aisles(load_map(map_file));
      } catch (const std::invalid_argument& e) {  // a map without shelf aisles is bad input (was rc 1)
        std::string what = e.what();
        if (what.rfind("one_way_aisles: ", 0) == 0) what.erase(0, 16);
        throw InputError("--one-way-aisles: " + what);
      }
    }();
    const Instance ins = load_scen(scen_file, g, agents);
    // std::bad_alloc (rc 1) otherwise; the default window fits every MovingAI map.
    if (const double cells = (static_cast<double>(lns_window) + 1) * g.size();
        lns_window_opt->count() > 0 && cells > static_cast<double>(1 << 28))
      throw InputError("--lns-window " + std::to_string(lns_window) + ": the LNS table of (window + 1) x " +
                       std::to_string(g.size()) + " vertices exceeds 2^28 cells");

    LacamOptions lopt;
    lopt.swap = !no_swap;
    // Default: RT-LaCAM* only (measured: docs/rt_lacam_star.md, session 36); LaCAM and the
    // paper's RT-LaCAM keep LaCAM's PIBT, so that they build the same tree (bench_planner.py).
    if (free_first_opt->count() == 0) free_first = refine && parse_solver(solver) == Solver::RtLacam;
    lopt.free_first = free_first;
    if (highways_opt->count() == 0) highways = default_highways(parse_solver(solver), refine);
    lopt.highways = highways;
    lopt.highway_min_run = highway_min_run;
    lopt.seed = seed;
    lopt.refine = refine;
    lopt.restart_rate = restart_rate;
    lopt.lns = lns;
    lopt.lns_window = lns_window;
    lopt.lns_agents = lns_agents;
    lopt.lns_neighbourhood = parse_lns_neighbourhood(lns_nbh);
    lopt.refine_threads = refine_threads;
    if (iter_refine_opt->count() == 0) iter_refine = default_iter_refine(parse_solver(solver), refine, anytime_ms);
    lopt.iter_refine = iter_refine;
    lopt.objective = parse_objective(objective);
    lopt.scatter = scatter;
    lopt.scatter_margin = scatter_margin;
    lopt.scatter_lead = scatter_lead;
    lopt.scatter_max_passes = scatter_max_passes;
    lopt.scatter_dive_passes = scatter_dive_passes;
    lopt.dive = dive;
    lopt.scatter_first = scatter_first;
    lopt.scatter_live = scatter_live;
    lopt.scatter_live_share = scatter_live_share;
    lopt.scatter_live_keep = scatter_live_keep;
    lopt.scatter_dive_guard = scatter_dive_guard;
    lopt.reprice = reprice;
    lopt.lookahead = lookahead;
    lopt.scatter_lead_dive = scatter_lead_dive;
    lopt.scatter_prepare = scatter_prepare;
    lopt.guided_cost = guided_cost;
    lopt.dive_pause = dive_pause;
    lopt.cold_end = cold_end;
    lopt.cold_factor = cold_factor;
    lopt.scatter_lead_guided = scatter_lead_guided;
    lopt.resumable = resumable;
    lopt.pause_min_ms = pause_min_ms;
    lopt.mc_rollouts = mc_rollouts;
    lopt.mc_first = mc_first;
    lopt.mc_refine = mc_refine;
    lopt.lg_window = lg_window;
    lopt.lg_first = lg_first;
    lopt.lg_window_unpaused = lg_window_unpaused;
    lopt.lg_rest = lg_rest;
    lopt.lg_collision_weight = lg_weight;
    lopt.lg_refine = lg_refine;
    lopt.lg_refresh = lg_refresh;
    lopt.lg_budget = lg_budget;
    lopt.lg_repair = lg_repair;
    lopt.lg_gate = lg_gate;
    RunOptions ropt;
    // An expansions budget alone is deterministic: the default 1 ms wall cutoff would cut its
    // iterations by the machine's speed and load.
    const bool wall = budget_expansions == 0 || cutoff_opt->count() > 0;
    ropt.per_iteration = wall ? Budget::time_ms(cutoff_ms) : Budget::unlimited();
    if (reserve) ropt.per_iteration.reserve_ms = 1e-6;  // on; the costliest expansion so far sets it
    if (budget_expansions > 0) ropt.per_iteration.expansions = budget_expansions;
    ropt.timeout_ms = timeout_s * 1000.0;
    ropt.max_steps = max_steps;
    ropt.record_plan = !out_file.empty() || action_model == "rotation";
    // Progress on stderr for runs longer than --progress-s (stdout stays one JSON object).
    const auto started = Clock::now();
    auto last = started;
    if (progress_s > 0) {
      ropt.progress_ms = progress_s * 1000;
      ropt.on_progress = [&](const RunResult& s) {
        if (ms_since(last) < progress_s * 1000) return;
        last = Clock::now();
        std::cerr << "[rtlacam-bench] " << solver << " N=" << agents << ": " << s.iterations << " iterations, planning "
                  << s.total_planning_ms / 1000 << " s of " << timeout_s << " s, " << s.expansions
                  << " expansions, wall " << ms_since(started) / 1000 << " s" << std::endl;
      };
    }
    ropt.anytime_ms = anytime_ms;

    // The policy: loaded before the clock starts (a one-off, like reading the map).
    policy::Model model;
    std::unique_ptr<policy::PolicyPreference> pref;
    if (!policy_file.empty()) {
      model = policy::load_weights(policy_file);
      pref = std::make_unique<policy::PolicyPreference>(g, model, ins.goals);
    }

    RunResult r;
    nlohmann::json threads_json;  // refiner threads' counts (only with --refine-threads)
    if (!is_realtime(parse_solver(solver))) {
      r = run_full_horizon(g, ins.starts, ins.goals, lopt, ropt, pref.get());
    } else {
      // Construction (distance tables, the root node) counts as planning time, as it
      // does inside run_full_horizon for LaCAM.
      const auto t0 = Clock::now();
      SolverOptions sopt;
      sopt.seed = seed;
      sopt.lacam = lopt;
      sopt.pref = pref.get();
      std::unique_ptr<RealtimePlanner> p = make_planner(parse_solver(solver), g, ins.starts, ins.goals, sopt);
      const double setup_ms = ms_since(t0);
      std::ofstream trace;
      if (const auto* rt = dynamic_cast<const RtLacam*>(p.get()); rt && !trace_best.empty()) {
        trace.open(trace_best);
        if (!trace) throw InputError("--trace-best: cannot write " + trace_best);
        ropt.record_plan = true;
        // Outside the iterations' timing (runner.cpp calls it between them).
        ropt.on_progress = [&, rt](const RunResult& s) {
          const std::vector<Config> ahead = rt->lacam().best_path();
          long long soc = -1;
          if (!ahead.empty()) {
            Validator v(g, ins.starts, ins.goals);
            for (size_t t = 1; t < s.plan.size(); ++t) v.step(s.plan[t]);
            for (size_t t = 1; t < ahead.size(); ++t) v.step(ahead[t]);
            soc = v.ok() ? v.sum_of_costs() : -2;
          }
          trace << s.iterations << ' ' << soc << '\n';
        };
      }
      r = run_realtime(*p, g, ins.starts, ins.goals, ropt);
      r.total_planning_ms += setup_ms;
      if (const auto* rt = dynamic_cast<const RtLacam*>(p.get()); rt) {  // refinement's counts
        threads_json["lns_steps"] = rt->lacam().lns_cost().samples();  // timed LNS steps learnt from
        threads_json["lns_max_window"] = rt->lacam().lns_max_window();
        threads_json["dives"] = rt->lacam().dives();
        threads_json["dive_wins"] = rt->lacam().dive_wins();
        threads_json["dive_stalls"] = rt->lacam().dive_stalls();
        threads_json["reprices"] = rt->lacam().reprices();
        threads_json["lookaheads"] = rt->lookaheads();  // directed graphs (rt_lacam.hpp)
        threads_json["lookahead_switches"] = rt->switches();
        threads_json["rewire_cuts"] = rt->lacam().rewire_cuts();
        threads_json["late_dives"] = rt->lacam().late_dives();
        threads_json["dive_pauses"] = rt->lacam().dive_pauses();
        threads_json["cold_steps"] = rt->lacam().cold_steps();
        threads_json["highway_arcs"] = rt->lacam().highway_arcs();
        threads_json["guided_expansions_timed"] = rt->lacam().guided_expansion_cost().samples();
        threads_json["scatter_lead_used"] = rt->lacam().scatter_lead();
        threads_json["lg_nodes"] = rt->lacam().lg_nodes();
        threads_json["lg_kept"] = rt->lacam().lg_kept();
        if (iter_refine) {
          threads_json["iter_groups"] = rt->lacam().iter_groups();
          threads_json["iter_kept"] = rt->lacam().iter_kept();
          threads_json["iter_resets"] = rt->lacam().iter_resets();
          threads_json["iter_windows"] = rt->lacam().iter_windows();
          threads_json["iter_refused"] = rt->lacam().iter_refused();
        }
      }
      if (const auto* rt = dynamic_cast<const RtLacam*>(p.get()); rt && refine_threads > 0) {
        threads_json["refine_threads"] = refine_threads;
        threads_json["thread_windows"] = rt->lacam().thread_windows();  // adopted
        threads_json["thread_wins"] = rt->lacam().thread_wins();        // of them, cheaper
        threads_json["thread_refused"] = rt->lacam().thread_refused();
      }
    }

    const long long soc_lb = ins.soc_lower_bound(g);
    nlohmann::json j;
    j["solved"] = r.solved;
    j["total_planning_ms"] = r.total_planning_ms;
    j["iterations"] = r.iterations;
    j["soc"] = r.soc;  // standard: up to each agent's last arrival (validator.hpp)
    j["sum_of_loss"] = r.sum_of_loss;
    j["makespan"] = r.makespan;
    j["soc_lb"] = soc_lb;
    j["norm_soc"] = r.solved && soc_lb > 0 ? static_cast<double>(r.soc) / static_cast<double>(soc_lb) : 0.0;
    j["norm_loss"] = r.solved && soc_lb > 0 ? static_cast<double>(r.sum_of_loss) / static_cast<double>(soc_lb) : 0.0;
    j["expansions"] = r.expansions;
    j["explored"] = r.explored;
    j["max_iteration_ms"] = r.max_iteration_ms;
    j["p99_iteration_ms"] = r.p99_iteration_ms;
    j["max_iteration_cpu_ms"] = r.max_iteration_cpu_ms;
    j["p99_iteration_cpu_ms"] = r.p99_iteration_cpu_ms;
    j["solver"] = solver;
    j["cutoff_ms"] = wall ? nlohmann::json(cutoff_ms) : nlohmann::json(nullptr);  // null: no wall cutoff
    j["budget_expansions"] = budget_expansions;
    j["reserve"] = reserve;
    j["resumable"] = resumable;
    j["pause_min_ms"] = pause_min_ms;
    j["mc_rollouts"] = mc_rollouts;
    j["mc_first"] = mc_first;
    j["mc_refine"] = mc_refine;
    j["local_guidance"] = lg_window;
    j["lg_first"] = lg_first;
    j["lg_window_unpaused"] = lg_window_unpaused;
    j["lg_rest"] = lg_rest;
    j["lg_collision_weight"] = lg_weight;
    j["lg_refine"] = lg_refine;
    j["lg_refresh"] = lg_refresh;
    j["lg_budget"] = lg_budget;
    j["lg_repair"] = lg_repair;
    j["lg_gate"] = lg_gate;
    j["swap"] = !no_swap;
    j["free_first"] = free_first;
    j["highways"] = highways;
    j["highway_min_run"] = highway_min_run;
    j["iter_refine"] = iter_refine;
    j["refine"] = refine;
    j["anytime_ms"] = anytime_ms;
    j["lns"] = lns;
    j["lns_window"] = lns_window;
    j["objective"] = objective;
    j["lns_agents"] = lns_agents;
    j["lns_neighbourhood"] = lns_nbh;
    for (auto it = threads_json.begin(); it != threads_json.end(); ++it) j[it.key()] = it.value();
    j["scatter"] = scatter;
    j["scatter_margin"] = scatter_margin;
    j["scatter_lead"] = scatter_lead;
    j["scatter_max_passes"] = scatter_max_passes;
    j["scatter_dive_passes"] = scatter_dive_passes;
    j["dive"] = dive;
    j["scatter_first"] = scatter_first;
    j["scatter_live"] = scatter_live;
    j["scatter_live_share"] = scatter_live_share;
    j["scatter_live_keep"] = scatter_live_keep;
    j["scatter_dive_guard"] = scatter_dive_guard;
    j["reprice"] = reprice;
    j["lookahead"] = lookahead;
    j["scatter_lead_dive"] = scatter_lead_dive;
    j["scatter_prepare"] = scatter_prepare;
    j["guided_cost"] = guided_cost;
    j["dive_pause"] = dive_pause;
    j["cold_end"] = cold_end;
    j["cold_factor"] = cold_factor;
    j["scatter_lead_guided"] = scatter_lead_guided;
    j["seed"] = seed;
    j["map"] = map_file;
    j["scen"] = scen_file;
    j["agents"] = agents;
    j["no_solution"] = r.no_solution;
    j["timed_out"] = r.timed_out;
    j["step_limit"] = r.step_limit;
    j["valid"] = r.validation_error.empty();
    if (!r.validation_error.empty()) j["validation_error"] = r.validation_error;
    if (pref) {
      j["policy"] = policy_file;
      j["policy_inferences"] = pref->inferences();
      j["policy_ms"] = pref->observation_ms() + pref->forward_ms();
    }
    j["action_model"] = action_model;
    if (action_model == "rotation") {
      const executor::RotationRun rr = executor::run_with_rotation(g, r.plan);
      j["rotation_makespan"] = rr.makespan;
      j["rotation_soc"] = rr.soc;
      j["rotation_turns"] = rr.turns;
      j["valid"] = r.validation_error.empty() && rr.error.empty();
      if (!rr.error.empty() && r.validation_error.empty()) r.validation_error = "rotation: " + rr.error;
      if (!rr.error.empty()) j["validation_error"] = r.validation_error;
    }
    std::cout << (compact ? j.dump() : j.dump(2)) << std::endl;

    if (!out_file.empty()) {
      PlanHeader h;
      h.map_file = map_file;
      h.solver = solver;
      h.solved = r.solved;
      h.soc = r.soc;
      h.soc_lb = soc_lb;
      h.makespan = r.makespan;
      h.comp_time_ms = r.total_planning_ms;
      h.extra = {{"cutoff_ms", wall ? std::to_string(cutoff_ms) : std::string("none")}, {"seed", std::to_string(seed)},
                 {"sum_of_loss", std::to_string(r.sum_of_loss)}};
      write_file(out_file, [&](std::ostream& out) { write_plan(out, g, ins.starts, ins.goals, r.plan, h); });
    }
    if (!r.validation_error.empty()) {
      std::cerr << "rtlacam-bench: invalid plan: " << r.validation_error << std::endl;
      return cli::kInvalidPlan;
    }
    return r.solved ? cli::kOk : cli::kUnsolved;
  } catch (const InputError& e) {
    std::cerr << "rtlacam-bench: " << e.what() << std::endl;
    return cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "rtlacam-bench: error: " << e.what() << std::endl;
    return cli::kRuntimeError;
  }
}
