#pragma once
// Command-line binders of the lifelong apps: a group of options, bound to a CLI11 app
// (bind), checked and turned into the library's options (apply) with one-line
// planner::InputError messages, and described in the run's JSON (describe).
//   SolverCli  --solver, --seed, --policy and every solver's options (planner/solver.hpp)
//   ExecCli    --executor and the delay model (executor/: grid4 plans, and the rotation solvers' with headings)
//   TaskCli    the task layer (tasks/task_layer.hpp): mode, assigner, queues, parking, urgency and
//   BatteryCli --battery-* and --chargers: batteries and charging errands (tasks/battery.hpp)
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli.hpp"
#include "executor/delay_model.hpp"
#include "executor/graph_execution.hpp"
#include "planner/error.hpp"
#include "planner/rotation/guidance.hpp"
#include "planner/rotation/traffic_flow.hpp"
#include "planner/rotation_settings.hpp"
#include "planner/solver.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/lorr_problem.hpp"
#include "tasks/task_layer.hpp"
#include "tasks/station_queues.hpp"
#include "tasks/task_manager.hpp"

namespace cli {

struct SolverCli {
  std::string solver = "rtlacam", policy_file;
  uint64_t seed = 0;
  bool refine = true, reset_priorities = false, rot_back_last = true, rot_pocket_exit = true;
  // Off by default in lifelong runs: on MR23-I-10 (warehouse_large, 600 / 1500 agents, 5 ms) it
  // gave +1.8 / +2.1 % errands but 2.1-2.3x the peak memory (a second table per goal) and a first
  // expansion of each epoch 7-13x slower (new goals' guide tables are not prefetched).
  int highways = 0;
  // Default arrows (pibt-rot, epibt): +8 to +20 % errands/step for pibt-rot on all five
  // MR23 instances (5 seeds) and on RANDOM-01..05 (docs/rotation_lorr.md "Guidance graph").
  std::string guidance = "arrows", guidance_costs = "1,3,1";
  planner::Epibt::Options ep;
  std::string ep_priority = "distance";
  // Online traffic-flow guide paths for epibt (planner/traffic_flow.hpp; docs/rotation_lorr.md "Traffic flow").
  // Default on for epibt (rotation): +2 to +69 % errands/step on MR23, 5 seeds (docs/rotation_lorr.md "Traffic flow").
  std::string traffic_flow = "on", tf_weights = "1,0.1";
  bool tf_active = true;
  planner::WpplOptions wppl;
  // The learned policy (loaded by apply; it must outlive the run).
  policy::Model model;
  std::unique_ptr<policy::PolicyPreference> pref;

  void bind(CLI::App& app)
  {
    app.add_flag("--refine,!--no-refine", refine,
                 "rtlacam: LaCAM* refinement after each epoch's first solution (RT-LaCAM*); --no-refine: the paper's RT-LaCAM")
        ->capture_default_str();
    app.add_option("--highways", highways,
                   "rtlacam (grid4): PIBT's soft one-way aisles, a move against a corridor's grain ranks as "
                   "1 + P (planner/highways.hpp); 0 = off")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    app.add_flag("--reset-priorities", reset_priorities,
                 "start PIBT priorities again from distance/N at every goal change (default: keep them)");
    app.add_option("--policy", policy_file, "learned policy weights: PIBT tries moves in its order (CS-PIBT)");
    app.add_option("--solver", solver,
                   planner::solver_names(true) +
                       " (cspibt: pibt ordered by --policy; pibt-rot: PIBT over (cell, heading); epibt: PIBT with "
                       "multi-action operations; wppl: windowed LNS over pibt-rot rollouts; the last three rotation only)")
        ->check(CLI::IsMember(planner::solver_list(true)))
        ->capture_default_str();
    app.add_option("--seed", seed, "random seed")->capture_default_str();
    app.add_flag("--rot-back-last,!--no-rot-back-last", rot_back_last,
                 "pibt-rot: a robot asked to vacate its cell tries the cell behind it last")
        ->capture_default_str();
    app.add_flag("--rot-pocket-exit,!--no-rot-pocket-exit", rot_pocket_exit,
                 "pibt-rot, wppl: no move deeper into a dead-end pocket that a robot in it has to leave "
                 "(planner/rotation/pocket_exit.hpp; epibt: --epibt-pocket-exit)")
        ->capture_default_str();
    app.add_option("--guidance", guidance,
                   "pibt-rot, epibt, wppl: none | arrows (one-way lanes: rows alternate east/west, columns south/north) | "
                   "FILE (forward costs per cell and heading, planner/guidance.hpp); default arrows, wppl: none; other "
                   "solvers: none")
        ->capture_default_str();
    app.add_option("--guidance-costs", guidance_costs, "--guidance arrows: ALONG,AGAINST,TURN costs (1..60)")
        ->capture_default_str();
    app.add_option("--epibt-depth", ep.depth, "epibt: actions per operation")->check(CLI::Range(3, 5))->capture_default_str();
    app.add_option("--epibt-revisit", ep.revisit, "epibt: replans of one robot per step at most")
        ->check(cli::positive())
        ->capture_default_str();
    app.add_option("--epibt-lns-revisit", ep.lns_revisit, "epibt: the same limit in the LNS rounds")
        ->check(cli::positive())
        ->capture_default_str();
    app.add_flag("--epibt-inherit,!--no-epibt-inherit", ep.inherit,
                 "epibt: each step starts from the tails of the last step's operations")
        ->capture_default_str();
    app.add_flag("--epibt-pocket-exit,!--no-epibt-pocket-exit", ep.pocket_exit,
                 "epibt: no operation goes deeper into a dead-end pocket that a robot in it has to leave (needs --urgency-stalls' pockets)")
        ->capture_default_str();
    app.add_flag("--epibt-leavers-first,!--no-epibt-leavers-first", ep.leavers_first,
                 "epibt, with --epibt-pocket-exit: a robot that must leave a dead-end pocket ranks above all others")
        ->capture_default_str();
    app.add_flag("--epibt-wait-op", ep.wait_op,
                 "epibt: WWW among every robot's candidates (default: only kept when nothing else fits)");
    app.add_option("--epibt-lns", ep.lns_rounds,
                   "epibt: LNS rounds after the pass (EPIBT+LNS; -1: until the step's deadline, timing-dependent); 0 = off")
        ->check(CLI::Range(-1, 1000000))
        ->capture_default_str();
    app.add_flag("--epibt-lns-converge,!--no-epibt-lns-converge", ep.lns_converge,
                 "epibt: LNS stops after a round that gained nothing")
        ->capture_default_str();
    app.add_option("--epibt-priority", ep_priority, "epibt: distance (nearest goal first, the paper's) | age (pibt-rot's)")
        ->check(CLI::IsMember({"distance", "age"}))
        ->capture_default_str();
    app.add_option("--traffic-flow", traffic_flow,
                   "epibt: off | on (congestion-aware guide path per robot, computed online; default on for epibt)")
        ->check(CLI::IsMember({"off", "on"}))
        ->capture_default_str();
    app.add_option("--tf-weights", tf_weights, "--traffic-flow on: CONTRAFLOW,VERTEX weights (0..1000) of the congestion costs")
        ->capture_default_str();
    app.add_option("--tf-refresh", ep.tf.refresh, "--traffic-flow on: guide paths re-planned per step beyond goal changes")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_option("--wppl-window", wppl.window, "wppl: steps planned ahead (W)")->check(cli::positive())->capture_default_str();
    app.add_option("--wppl-neighbourhood", wppl.neighbourhood, "wppl: robots replanned per LNS iteration")
        ->check(cli::positive())
        ->capture_default_str();
    app.add_flag("--wppl-pareto,!--no-wppl-pareto", wppl.pareto,
                 "wppl: accept LNS paths only if no robot of the neighbourhood is worse off")
        ->capture_default_str();
    app.add_flag("--wppl-ties,!--no-wppl-ties", wppl.accept_ties,
                 "wppl: LNS also keeps new paths of equal windowed cost (sideways moves)")
        ->capture_default_str();
    app.add_flag("--wppl-tail,!--no-wppl-tail", wppl.reuse_tail,
                 "wppl: start from the last window's refined tail when it beats the PIBT rollout")
        ->capture_default_str();
  }

  // The solver's options for `agents` robots on `g`; loads the policy. Throws InputError.
  void apply(const CLI::App& app, const planner::Graph& g, size_t agents, bool rotation, planner::SolverOptions& so)
  {
    const planner::Solver kind = planner::parse_solver(solver);
    if (planner::plans_rotation(kind) && !rotation)
      throw planner::InputError("--solver " + solver + " plans LoRR rotation actions: --action-model grid4 cannot run it (leave it out, or --action-model rotation)");
    if (planner::needs_policy(kind) && policy_file.empty()) throw planner::InputError("--solver cspibt needs --policy WEIGHTS");
    // The policy is told the goals by the planner (ActionPreference::set_goals).
    if (!policy_file.empty()) {
      model = policy::load_weights(policy_file);
      pref = std::make_unique<policy::PolicyPreference>(g, model, planner::Config{});
    }
    so.pref = pref.get();
    so.lacam.keep_priorities = !reset_priorities;
    so.lacam.refine = refine;
    if (highways > 0 && kind != planner::Solver::RtLacam && kind != planner::Solver::Naive)
      throw planner::InputError("--highways needs --solver rtlacam or naive (a LaCAM planner)");
    so.lacam.highways = highways;
    so.back_last = rot_back_last;
    so.pocket_exit = rot_pocket_exit;
    if (!planner::plans_rotation(kind) && app.count("--guidance") && guidance != "none")
      throw planner::InputError("--guidance needs a rotation-native solver (--solver pibt-rot, epibt or wppl)");
    // Unless asked, the solver's defaults, shared with Python (planner/rotation_settings.hpp:
    // arrows for pibt-rot and epibt, none for wppl; traffic flow for epibt).
    const planner::RotationSettings defaults = planner::RotationSettings::lifelong(kind);
    if (!app.count("--guidance")) guidance = defaults.guidance;
    if (!app.count("--traffic-flow")) traffic_flow = defaults.traffic_flow ? "on" : "off";
    if (guidance != "none") {
      if (guidance == "arrows") {
        int along = 0, against = 0, turn = 0;
        char end = 0;
        if (std::sscanf(guidance_costs.c_str(), "%d,%d,%d%c", &along, &against, &turn, &end) != 3)
          throw planner::InputError("--guidance-costs '" + guidance_costs + "': expected ALONG,AGAINST,TURN");
        try {
          so.guidance = planner::arrow_guidance(g, along, against, turn);
        } catch (const std::invalid_argument& e) {
          throw planner::InputError(std::string("--guidance-costs: ") + e.what());
        }
      } else {
        so.guidance = planner::load_guidance(g, guidance);
      }
    }
    ep.priority = ep_priority == "age" ? planner::Epibt::Priority::Age : planner::Epibt::Priority::Distance;
    if (traffic_flow == "on" && kind != planner::Solver::Epibt) throw planner::InputError("--traffic-flow on needs --solver epibt");
    if (traffic_flow == "on") {
      char end = 0;
      if (std::sscanf(tf_weights.c_str(), "%lf,%lf%c", &ep.tf.contraflow, &ep.tf.vertex, &end) != 2 ||
          !(ep.tf.contraflow >= 0) || !(ep.tf.vertex >= 0) || ep.tf.contraflow > 1000 || ep.tf.vertex > 1000)
        throw planner::InputError("--tf-weights '" + tf_weights + "': expected CONTRAFLOW,VERTEX, each 0..1000");
      ep.tf.on = true;
      // Epibt keeps it off where the per-robot tables would not fit (TrafficFlowOptions::max_entries).
      if (!planner::TrafficFlow::fits(agents, g.size(), ep.tf)) {
        if (app.count("--traffic-flow"))
          std::cerr << "--traffic-flow on: off for this run (" << agents << " robots x 4 x " << g.size()
                    << " cells of guide tables > " << ep.tf.max_entries << " entries)\n";
        tf_active = false;
      }
    }
    so.epibt = ep;
    so.wppl = wppl;
  }

  // The solver's fields of the run's JSON.
  void describe(nlohmann::json& j) const
  {
    if (guidance != "none") j["guidance"] = guidance == "arrows" ? "arrows " + guidance_costs : guidance;
    if (ep.tf.on)
      j["trafficFlow"] = {{"active", tf_active}, {"contraflow", ep.tf.contraflow}, {"vertex", ep.tf.vertex}, {"refresh", ep.tf.refresh}};
    if (pref) j["policy"] = policy_file;
    j["keepPriorities"] = !reset_priorities;
    if (highways > 0) j["highways"] = highways;
  }
};

struct ExecCli {
  std::string mode;  // "" = none: every commit is executed at once
  executor::ExecOptions exec;
  executor::DelaySpec delays;
  std::vector<std::string> slow, stuck;

  void bind(CLI::App& app)
  {
    app.add_option("--executor", mode,
                   "execute commits under delays: lockstep | adg | adg-follow (default: none, every commit is executed at once)")
        ->check(CLI::IsMember({"lockstep", "adg", "adg-follow"}));
    app.add_option("--window", exec.window, "adg: committed configurations ahead of the slowest agent (>= 1)")->capture_default_str();
    app.add_option("--delay-kind", delays.kind, "none | bernoulli | poisson")->capture_default_str();
    app.add_option("--delay-p", delays.p, "bernoulli: per agent per step probability that a stop starts");
    app.add_option("--delay-rate", delays.rate, "poisson: stop events per agent per step");
    app.add_option("--delay-min", delays.min_ticks, "shortest stop, steps")->capture_default_str();
    app.add_option("--delay-max", delays.max_ticks, "longest stop, steps")->capture_default_str();
    app.add_option("--delay-fraction", delays.fraction, "share of the agents that ever stop")->capture_default_str();
    app.add_option("--delay-seed", delays.seed, "seed of the delays")->capture_default_str();
    app.add_option("--slow", slow, "AGENT:FACTOR, a slowed agent (factor in (0, 1]); repeatable");
    app.add_option("--stuck", stuck, "AGENT:AT:STEPS, an agent stopped from step AT for STEPS; repeatable");
  }

  // opt.graph_execution, opt.exec and opt.delays for a team of `agents`. Throws InputError.
  void apply(int agents, tasks::LifelongOptions& opt)
  {
    if (mode.empty()) {
      if (delays.kind != "none" || !slow.empty() || !stuck.empty())
        throw planner::InputError("delay options need --executor lockstep|adg");
      return;
    }
    exec.mode = mode;
    for (const std::string& s : slow) {
      executor::Slowdown d;
      if (std::sscanf(s.c_str(), "%d:%lf", &d.agent, &d.factor) != 2) throw planner::InputError("--slow '" + s + "': expected AGENT:FACTOR");
      delays.slow.push_back(d);
    }
    for (const std::string& s : stuck) {
      executor::Stuck d;
      if (std::sscanf(s.c_str(), "%d:%lld:%lld", &d.agent, &d.at, &d.ticks) != 3)
        throw planner::InputError("--stuck '" + s + "': expected AGENT:AT:STEPS");
      delays.stuck.push_back(d);
    }
    if (std::string e = executor::check(exec); !e.empty()) throw planner::InputError("--" + e);
    if (std::string e = executor::check(delays, agents); !e.empty()) throw planner::InputError("--delay " + e);
    opt.graph_execution = true;
    opt.exec = exec;
    opt.delays = delays;
  }
};

// The model and options of the SUMO controller's fleet.battery (controller/README.md), on
// the grid: cells 1 m apart, 1 s steps, chargers at the cells of --chargers (the
// agents-file format: a count, then cell ids), each giving --battery-charge-w watts.
// Any of these options turns the battery on.
struct BatteryCli {
  tasks::BatteryOptions o;
  double charge_w = tasks::BatterySetup{}.charge_w;
  std::string chargers_file;
  bool no_charging = false, no_rematch = false, no_task_check = false;
  std::vector<CLI::Option*> opts;

  void bind(CLI::App& app)
  {
    opts.push_back(app.add_option("--battery-capacity-wh", o.capacity_wh, "battery: capacity (Wh)")->capture_default_str());
    opts.push_back(app.add_option("--battery-initial", o.initial, "battery: charge at the start, fraction of capacity")->capture_default_str());
    opts.push_back(app.add_option("--battery-per-m-wh", o.per_m_wh, "battery: drain per metre (a cell)")->capture_default_str());
    opts.push_back(app.add_option("--battery-per-turn-wh", o.per_turn_wh, "battery: drain per change of direction")->capture_default_str());
    opts.push_back(app.add_option("--battery-threshold", o.threshold,
                                  "battery: below it, between tasks, an agent goes to charge (fraction)")->capture_default_str());
    opts.push_back(app.add_option("--battery-critical", o.critical,
                                  "battery: below it mid-task an agent hands its task back and charges (fraction, < threshold; 0 = off)")
                       ->capture_default_str());
    opts.push_back(app.add_option("--battery-reserve-margin", o.reserve_margin,
                                  "battery: also low / critical below this x the energy of the way to the nearest charger (0 = off)")
                       ->capture_default_str());
    opts.push_back(app.add_option("--battery-target", o.target, "battery: an agent leaves the charger at this fraction")->capture_default_str());
    opts.push_back(app.add_option("--battery-charge-w", charge_w, "battery: each charger's power (W; 1 s steps)")->capture_default_str());
    opts.push_back(app.add_flag("--battery-no-charging", no_charging, "battery: drain only, no charging errands"));
    opts.push_back(app.add_flag("--battery-no-rematch", no_rematch, "battery: agents on their way to chargers never swap claims"));
    opts.push_back(app.add_flag("--battery-no-task-check", no_task_check,
                                "battery: give a task without checking that the charge covers it and the way on to a charger"));
    opts.push_back(app.add_option("--chargers", chargers_file, "battery: charger cells (the agents-file format: a count, then cell ids)"));
  }

  bool on() const
  {
    for (const CLI::Option* x : opts)
      if (x->count() > 0) return true;
    return false;
  }

  // The battery of the task layer (checked when it is set: make_task_layer).
  void fill(const planner::Graph& g, tasks::BatterySetup& b) const
  {
    b.on = on();
    if (!b.on) return;
    b.options = o;
    b.options.charging = !no_charging;
    b.options.rematch = !no_rematch;
    b.options.task_check = !no_task_check;
    b.charge_w = charge_w;
    if (!chargers_file.empty()) {
      const planner::Config c = tasks::load_lorr_agents(chargers_file, g);
      b.charger_cells.assign(c.begin(), c.end());
    }
  }

  // make_task_layer's "battery.key: what" under this group's option names.
  static planner::InputError error(const std::string& what)
  {
    const std::string rest = what.substr(what.find('.') + 1);
    const std::string key = rest.substr(0, rest.find(':'));
    std::string name = key == "chargers" ? "--chargers" : "--battery-" + key;
    for (char& ch : name) ch = ch == '_' ? '-' : ch;
    return planner::InputError(name + rest.substr(key.size()));
  }
};

// The task layer (tasks/task_layer.hpp): --mode, --assigner, --pool-size, --k-nearest,
// --reassign, --urgency, --queue-*, --parking and the battery (BatteryCli); make() fills
// tasks::TaskLayerOptions and builds it with tasks::make_task_layer, as the controller's YAML
// and Python do.
struct TaskCli {
  std::string mode, assigner = "greedy", parking_file;
  int pool_size = 0;  // 0: the problem's (LorrProblem::pool_size)
  tasks::TaskLayerOptions o;
  bool urgency = false;
  std::string urgency_stalls, urgency_battery;  // "": as --urgency; "true" | "false": that hint alone
  BatteryCli battery;
  CLI::Option* in_line_opt = nullptr;  // --queue-in-line: given, or the solver's default (default_in_line)

  void bind(CLI::App& app)
  {
    app.add_option("--mode", mode, "roundrobin | pool (default: roundrobin for 2023 roundrobin problems, else pool)")
        ->check(CLI::IsMember({"roundrobin", "pool"}));
    app.add_option("--assigner", assigner, "pool mode: greedy | hungarian")
        ->check(CLI::IsMember({"greedy", "hungarian"}))
        ->capture_default_str();
    app.add_option("--pool-size", pool_size, "pool mode: tasks revealed at once (default: the problem's numTasksReveal x teamSize)")
        ->check(CLI::Range(1, 10000000));  // numTasksReveal x teamSize's bound: 2^31 ran out of memory
    app.add_flag("--reassign,!--no-reassign", o.reassign,
                 "pool mode: a free agent strictly nearer to a task not yet opened may take it from its holder "
                 "(default off: assignments are kept until the task is done; helps open maps, hurts LoRR's WAREHOUSE)");
    app.add_flag("--urgency,!--no-urgency", urgency,
                 "priority hints to the planner (tasks/urgency.hpp): a stalled errand's holder and a low-battery agent "
                 "win conflicts at each epoch start (default off here; on in rtlacam-sumo)");
    app.add_flag("--urgency-stalls{true},--no-urgency-stalls{false}", urgency_stalls,
                 "the stall hints alone, whatever --urgency says (tasks.urgency.stalls)");
    app.add_flag("--urgency-battery{true},--no-urgency-battery{false}", urgency_battery,
                 "the low-battery hints alone, whatever --urgency says (tasks.urgency.battery)");
    app.add_option("--stall-swap-after", o.urgency.swap_after,
                   "pool mode: a pick-up errand stalled this many ticks passes to a nearer agent heading for the "
                   "same station cell (tasks.urgency.swap_after; 0 = off)")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_option("--stall-head-after", o.urgency.head_after,
                   "per station cell, the agent stalled this many ticks outside its stub gets priority, and agents in a "
                   "stub that is not theirs leave first (tasks.urgency.head_after; 0 = off)")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_flag("--drop-hints,!--no-drop-hints", o.urgency.drop_hints,
                 "with --stall-head-after: every loaded agent stalled that long outside a pocket gets its stall as "
                 "priority, not only the head per drop station (tasks.urgency.drop_hints; default off)");
    app.add_flag("--sticky-stalls,!--no-sticky-stalls", o.urgency.sticky,
                 "stall hints and the stall handover read an errand's longest stall so far, not only the current one "
                 "(tasks.urgency.sticky; default off)");
    app.add_option("--escalate-after", o.urgency.escalate_after,
                   "starvation guard: per errand cell, the errand stalled longest, once this many ticks, gets the top "
                   "priority below battery and the epoch's goal test until it completes (tasks.urgency.escalate_after; "
                   "tasks/escalation.hpp; 0 = off)")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_option("--station-load-cost", o.urgency.load_cost,
                   "pool mode: extra moves charged per task already bound for a station (tasks.urgency.load_cost; 0 = off)")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_option("--pocket-cost", o.urgency.pocket_cost,
                   "PIBT ranks an agent's move into another station's dead-end stub this many moves worse "
                   "(tasks.urgency.pocket_cost; 0 = off)")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_option("--k-nearest", o.k_nearest, "hungarian: candidate tasks per agent")->check(cli::positive())->capture_default_str();
    app.add_option("--queue-capacity", o.queues.capacity,
                   "station queues: agents heading for one errand cell at once, the rest wait on queue cells before it "
                   "(tasks/station_queues.hpp); 0 = off")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_option("--queue-length", o.queues.length, "station queues: queue cells per station")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_option("--queue-admission", o.queues.admission,
                   "station queues, pool mode: tasks held at once with an errand left at one station "
                   "(0 = capacity + length, -1 = no limit)")
        ->check(CLI::Range(-1, 10000000))
        ->capture_default_str();
    app.add_flag("--queue-fifo,!--no-queue-fifo", o.queues.fifo,
                 "station queues: agents beyond a queue are taken oldest request first (default on; off: nearest first)");
    app.add_option("--queue-clear-after", o.queues.clear_after,
                   "station queues: a dead-end station whose stub held an agent that must get out this many steps "
                   "gives up its places until the stub is empty (tasks.queues.clear_after; 0 = off)")
        ->check(cli::non_negative())
        ->capture_default_str();
    app.add_flag("--queue-one-way,!--no-queue-one-way", o.queues.one_way,
                 "station queues: each station's queue lane is one-way towards the station in the planners' graph "
                 "(tasks.queues.one_way; default off)");
    app.add_option("--queue-jam-after", o.queues.jam_after,
                   "station queues: a station whose admitted agent came no nearer to it for this many steps "
                   "gives up its places until its stub and queue cells are empty (tasks.queues.jam_after; 0 = off)")
        ->check(cli::non_negative())
        ->capture_default_str();
    in_line_opt = app.add_flag("--queue-in-line,!--no-queue-in-line", o.queues.in_line,
                               "station queues: each step the admitted and queued agents of a station are re-ranked by "
                               "their distance to it, nearest admitted (YAML tasks.queues.in_line; default on with "
                               "--solver epibt, off otherwise)");
    app.add_flag("--queue-leavers-first,!--no-queue-leavers-first", o.queues.leavers_first,
                 "station queues, with --queue-clear-after: the agents leaving a clearing station's stub get the "
                 "leaving priority (tasks.queues.leavers_first; default off)");
    app.add_flag("--queue-idle-clear,!--no-queue-idle-clear", o.queues.idle_clear,
                 "station queues: idle agents do not rest on the cells beside a dead-end station's mouth (YAML "
                 "tasks.queues.idle_clear; default off)");
    app.add_option("--parking", parking_file,
                   "parking cells (the agents-file format: a count, then cell ids): idle agents wait there "
                   "(tasks/parking.hpp)");
    battery.bind(app);
  }

  // The graph the run plans on: `g`, or with --queue-one-way its one-way queue lanes
  // (tasks/station_queues.hpp one_way_queue_lanes). Throws InputError naming the option.
  planner::Graph graph(const planner::Graph& g, const tasks::TaskFile& file) const
  {
    if (!o.queues.on() || !o.queues.one_way) return g;
    try {
      return tasks::one_way_queue_lanes(g, file.errand_cells(), o.queues);
    } catch (const std::invalid_argument& e) {
      throw planner::InputError(std::string("--queue-one-way: ") + e.what());
    }
  }

  // --queue-in-line's default for `solver` (as the controller's tasks.queues.in_line): on for
  // epibt, which cannot undo a one-wide queue lane out of request order (controller/src/config.cpp).
  void default_in_line(const std::string& solver)
  {
    if (in_line_opt && in_line_opt->count() == 0) o.queues.in_line = tasks::in_line_by_default(solver);
  }

  // The task manager of `pr`'s tasks on `g` (mode: the problem's default unless --mode).
  // Throws InputError naming the option.
  std::unique_ptr<tasks::TaskManager> make(const tasks::LorrProblem& pr, const planner::Graph& g,
                                           std::shared_ptr<const tasks::TaskFile> file)
  {
    if (mode.empty()) mode = pr.default_mode();
    o.mode = mode;
    o.assigner = assigner;
    o.pool_size = pool_size > 0 ? pool_size : pr.pool_size();
    if (o.queues.admission > 0 && o.queues.admission < o.queues.capacity)
      throw planner::InputError("--queue-admission " + std::to_string(o.queues.admission) +
                                ": must be >= --queue-capacity, 0 or -1");
    if (o.queues.leavers_first && o.queues.clear_after == 0)
      throw planner::InputError("--queue-leavers-first: needs --queue-clear-after > 0 (it acts while a station clears its stub)");
    o.urgency.stalls = urgency_stalls.empty() ? urgency : urgency_stalls == "true";
    o.urgency.battery = urgency_battery.empty() ? urgency : urgency_battery == "true";
    if (!parking_file.empty()) {
      // The agents-file reader: a count, cell ids, each on the map and distinct.
      const planner::Config cells = tasks::load_lorr_agents(parking_file, g);
      o.parking = {true, std::vector<planner::Vertex>(cells.begin(), cells.end())};
    }
    battery.fill(g, o.battery);
    try {
      return tasks::make_task_layer(std::move(file), g, o);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      if (what.rfind("battery.", 0) == 0) throw BatteryCli::error(what);
      throw planner::InputError(what);
    }
  }
};

}  // namespace cli
