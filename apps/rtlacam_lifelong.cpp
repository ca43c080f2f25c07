// rtlacam-lifelong: a lifelong run on a LoRR problem (no SUMO). Prints a summary JSON
// (the log without per-step lists); --out writes the full LoRR / PlanViz log; progress goes
// to stderr.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "cli.hpp"
#include "planner/error.hpp"
#include "planner/output_file.hpp"
#include "planner/rotation/guidance.hpp"
#include "planner/solver.hpp"
#include "planner/stop_signal.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"
#include "tasks/lifelong_exec.hpp"
#include "tasks/lifelong_log.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_instance.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/solver.hpp"
#include "tasks/task_pool.hpp"

using namespace tasks;

int main(int argc, char** argv)
{
  CLI::App app{"Lifelong MAPF on a League of Robot Runners problem: task layer + real-time planner"};
  std::string problem_file, mode, assigner = "greedy", solver = "rtlacam", out_file, policy_file, action_model = "grid4";
  int rotation_window = 8;
  bool no_heading_ties = false;
  std::string heading_cost = "turns";
  size_t max_dist_tables = 0;
  bool reset_priorities = false, reassign = false, refine = true, prefetch = true, bound_queries = true;
  bool skip_late_search = false;
  double expansion_deviations = 4;
  long steps = -1;
  double budget_ms = 100, progress_s = 2;
  uint64_t budget_expansions = 0, seed = 0;
  int k_nearest = 32, agents = 0;
  bool quiet = false;
  // Execution under delays (executor/): off unless --executor is given.
  std::string executor_mode;
  executor::ExecOptions exec;
  executor::DelaySpec delays;
  std::vector<std::string> slow, stuck;
  app.add_option("--problem", problem_file, "LoRR problem JSON")->required();
  app.add_option("--steps", steps, "steps to simulate (default: the instance's simulation_time)");
  app.add_option("--agents", agents, "use only the first N agents of the team (default: teamSize)")->check(CLI::PositiveNumber);
  app.add_option("--mode", mode, "roundrobin | pool (default: roundrobin for 2023 roundrobin problems, else pool)")
      ->check(CLI::IsMember({"roundrobin", "pool"}));
  app.add_option("--assigner", assigner, "pool mode: greedy | hungarian")
      ->check(CLI::IsMember({"greedy", "hungarian"}))
      ->capture_default_str();
  app.add_flag("--reassign,!--no-reassign", reassign,
               "pool mode: a free agent strictly nearer to a task not yet opened may take it from its holder "
               "(default off: assignments are kept until the task is done; helps open maps, hurts LoRR's WAREHOUSE)");
  app.add_option("--k-nearest", k_nearest, "hungarian: candidate tasks per agent")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_flag("--prefetch,!--no-prefetch", prefetch,
               "grow the distance tables of upcoming goals in each step's spare budget (default on)");
  app.add_flag("--bound-queries,!--exact-queries", bound_queries,
               "distance queries past the step's deadline answer a lower bound instead of growing the table "
               "(default on; --exact-queries: every query runs its BFS on the spot)");
  app.add_flag("--skip-late-search,!--no-skip-late-search", skip_late_search,
               "rtlacam: a step with less time left than one expansion's cost bound makes none (agents follow the tree "
               "or wait) instead of overrunning its budget (default off: it costs throughput)");
  app.add_option("--expansion-deviations", expansion_deviations,
                 "the search stops this many mean deviations above the mean expansion cost before its deadline")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--max-dist-tables", max_dist_tables,
                 "distance tables kept (LRU; tables in use are kept beyond it); 0 = 2 x agents + 256");
  app.add_flag("--refine,!--no-refine", refine,
               "rtlacam: LaCAM* refinement after each epoch's first solution (RT-LaCAM*); --no-refine: the paper's RT-LaCAM")
      ->capture_default_str();
  app.add_flag("--reset-priorities", reset_priorities,
               "start PIBT priorities again from distance/N at every goal change (default: keep them)");
  app.add_option("--policy", policy_file, "learned policy weights: PIBT tries moves in its order (CS-PIBT)");
  std::vector<std::string> solvers = planner::solver_list(true);
  solvers.push_back(tasks::kRotationSolver);
  solvers.push_back(tasks::kEpibtSolver);
  solvers.push_back(tasks::kWpplSolver);
  app.add_option("--solver", solver, planner::solver_names(true) + " | pibt-rot | epibt | wppl (cspibt: pibt ordered by --policy; pibt-rot: PIBT over (cell, heading); epibt: PIBT with multi-action operations; wppl: windowed LNS over pibt-rot rollouts; the last three rotation only)")
      ->check(CLI::IsMember(solvers))
      ->capture_default_str();
  app.add_option("--budget-ms", budget_ms, "planning budget per step (wall clock)")
      ->check(cli::finite_range(0, 3.6e6))
      ->capture_default_str();
  app.add_option("--budget-expansions", budget_expansions, "also limit LaCAM expansions (wppl: LNS iterations) per step (deterministic); 0 = none");
  app.add_option("--seed", seed, "random seed")->capture_default_str();
  app.add_option("--action-model", action_model, "grid4 (4-connected moves) | rotation (LoRR MAPF_T: heading, a step per quarter turn)")
      ->check(CLI::IsMember({"grid4", "rotation"}))
      ->capture_default_str();
  app.add_option("--rotation-window", rotation_window, "rotation: plan steps the planner may run ahead of the slowest robot")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  bool rot_back_last = true;
  app.add_flag("--rot-back-last,!--no-rot-back-last", rot_back_last,
               "pibt-rot: a robot asked to vacate its cell tries the cell behind it last")
      ->capture_default_str();
  // Default arrows (pibt-rot, epibt): +8 to +20 % errands/step for pibt-rot on all five
  // MR23 instances (5 seeds) and on RANDOM-01..05 (docs/rotation_lorr.md "Guidance graph").
  std::string guidance = "arrows", guidance_costs = "1,3,1";
  app.add_option("--guidance", guidance,
                 "pibt-rot, epibt, wppl: none | arrows (one-way lanes: rows alternate east/west, columns south/north) | FILE "
                 "(forward costs per cell and heading, planner/guidance.hpp); default arrows, wppl: none; other solvers: none")
      ->capture_default_str();
  app.add_option("--guidance-costs", guidance_costs, "--guidance arrows: ALONG,AGAINST,TURN costs (1..60)")
      ->capture_default_str();
  planner::Epibt::Options ep;
  std::string ep_priority = "distance";
  app.add_option("--epibt-depth", ep.depth, "epibt: actions per operation")->check(CLI::Range(3, 5))->capture_default_str();
  app.add_option("--epibt-revisit", ep.revisit, "epibt: replans of one robot per step at most")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_flag("--epibt-inherit,!--no-epibt-inherit", ep.inherit, "epibt: each step starts from the tails of the last step's operations")->capture_default_str();
  app.add_flag("--epibt-wait-op", ep.wait_op, "epibt: WWW among every robot's candidates (default: only kept when nothing else fits)");
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
  // Online traffic-flow guide paths for epibt (planner/traffic_flow.hpp; docs/rotation_lorr.md "Traffic flow").
  // Default on for epibt (rotation): +2 to +69 % errands/step on MR23, 5 seeds (docs/rotation_lorr.md "Traffic flow").
  std::string traffic_flow = "on", tf_weights = "1,0.1";
  bool tf_active = true;
  app.add_option("--traffic-flow", traffic_flow, "epibt: off | on (congestion-aware guide path per robot, computed online; default on for epibt)")
      ->check(CLI::IsMember({"off", "on"}))
      ->capture_default_str();
  app.add_option("--tf-weights", tf_weights, "--traffic-flow on: CONTRAFLOW,VERTEX weights (0..1000) of the congestion costs")
      ->capture_default_str();
  app.add_option("--tf-refresh", ep.tf.refresh, "--traffic-flow on: guide paths re-planned per step beyond goal changes")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  planner::WpplOptions wppl;
  app.add_option("--wppl-window", wppl.window, "wppl: steps planned ahead (W)")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--wppl-neighbourhood", wppl.neighbourhood, "wppl: robots replanned per LNS iteration")
      ->check(CLI::PositiveNumber)
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
  app.add_flag("--no-heading-ties", no_heading_ties, "rotation: PIBT breaks distance ties at random, not by turns");
  app.add_option("--heading-cost", heading_cost,
                 "rotation: PIBT's move order: turns (rotation-aware cost in steps) or ties (distance, ties by turns)")
      ->check(CLI::IsMember({"turns", "ties"}));
  app.add_option("--out", out_file, "write the full LoRR / PlanViz log (paths, events, tasks) here");
  app.add_option("--progress-s", progress_s, "seconds between progress lines on stderr; 0 = none")->capture_default_str();
  app.add_flag("--quiet", quiet, "no progress lines");
  app.add_option("--executor", executor_mode, "execute commits under delays: lockstep | adg | adg-follow (default: none, every commit is executed at once)")
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
  cli::add_version(app, "rtlacam-lifelong");
  RTLACAM_PARSE(app, argc, argv);
  planner::install_stop_handlers();  // SIGINT / SIGTERM: stop stepping, write the log, exit 130 / 143

  try {
    const LorrInstance in = load_lorr_instance(problem_file, agents, "--agents ");
    const LorrProblem& pr = in.problem;
    const planner::Graph& g = in.g;
    const planner::Config& starts = in.starts;
    const std::shared_ptr<const TaskFile>& file = in.tasks;
    if (mode.empty()) mode = pr.default_mode();
    if (steps < 0) steps = pr.simulation_time;
    if (steps < 0) throw planner::input_error(problem_file, 0, "no simulation_time.json entry for this problem: pass --steps");

    std::unique_ptr<TaskManager> tm;
    if (mode == "roundrobin") tm = std::make_unique<RoundRobin>(file);
    else tm = std::make_unique<TaskPool>(file, g, pr.pool_size(), make_assigner(assigner, k_nearest), reassign);

    // The policy is told the goals by the planner (ActionPreference::set_goals).
    policy::Model model;
    std::unique_ptr<policy::PolicyPreference> pref;
    if (tasks::is_rotation_native(solver) && action_model != "rotation")
      throw planner::InputError("--solver " + solver + " plans LoRR rotation actions: it needs --action-model rotation");
    if (!tasks::is_rotation_native(solver) && planner::needs_policy(planner::parse_solver(solver)) && policy_file.empty()) throw planner::InputError("--solver cspibt needs --policy WEIGHTS");
    if (!policy_file.empty()) {
      model = policy::load_weights(policy_file);
      pref = std::make_unique<policy::PolicyPreference>(g, model, planner::Config{});
    }

    LifelongOptions opt;
    opt.pref = pref.get();
    opt.keep_priorities = !reset_priorities;
    opt.refine = refine;
    opt.prefetch = prefetch;
    opt.max_dist_tables = max_dist_tables;
    opt.bound_queries = bound_queries;
    opt.skip_late_search = skip_late_search;
    opt.expansion_deviations = expansion_deviations;
    opt.steps = steps;
    opt.action_model = parse_action_model(action_model);
    opt.rotation_window = rotation_window;
    opt.heading_ties = !no_heading_ties;
    opt.rot_back_last = rot_back_last;
    if (!tasks::is_rotation_native(solver)) {
      if (app.count("--guidance") && guidance != "none") throw planner::InputError("--guidance needs a rotation-native solver (--solver pibt-rot, epibt or wppl)");
      guidance = "none";
    }
    // wppl: arrows cost 5 % on MR23-I-04 and gain 1 % on I-03 (docs/rotation_lorr.md
    // "Where it stands"): unguided unless asked.
    if (solver == tasks::kWpplSolver && !app.count("--guidance")) guidance = "none";
    if (guidance != "none") {
      if (guidance == "arrows") {
        int along = 0, against = 0, turn = 0;
        char end = 0;
        if (std::sscanf(guidance_costs.c_str(), "%d,%d,%d%c", &along, &against, &turn, &end) != 3)
          throw planner::InputError("--guidance-costs '" + guidance_costs + "': expected ALONG,AGAINST,TURN");
        try {
          opt.guidance = planner::arrow_guidance(g, along, against, turn);
        } catch (const std::invalid_argument& e) {
          throw planner::InputError(std::string("--guidance-costs: ") + e.what());
        }
      } else {
        opt.guidance = planner::load_guidance(g, guidance);
      }
    }
    ep.priority = ep_priority == "age" ? planner::Epibt::Priority::Age : planner::Epibt::Priority::Distance;
    if (traffic_flow == "on" && solver != tasks::kEpibtSolver) {
      if (app.count("--traffic-flow")) throw planner::InputError("--traffic-flow on needs --solver epibt");
      traffic_flow = "off";  // the default applies to epibt only
    }
    if (traffic_flow == "on") {
      char end = 0;
      if (std::sscanf(tf_weights.c_str(), "%lf,%lf%c", &ep.tf.contraflow, &ep.tf.vertex, &end) != 2 || !(ep.tf.contraflow >= 0) ||
          !(ep.tf.vertex >= 0) || ep.tf.contraflow > 1000 || ep.tf.vertex > 1000)
        throw planner::InputError("--tf-weights '" + tf_weights + "': expected CONTRAFLOW,VERTEX, each 0..1000");
      ep.tf.on = true;
      // Epibt keeps it off where the per-robot tables would not fit (TrafficFlowOptions::max_entries).
      if (!planner::TrafficFlow::fits(starts.size(), g.size(), ep.tf)) {
        if (app.count("--traffic-flow"))
          std::cerr << "--traffic-flow on: off for this run (" << starts.size() << " robots x 4 x " << g.size()
                    << " cells of guide tables > " << ep.tf.max_entries << " entries)\n";
        tf_active = false;
      }
    }
    opt.epibt = ep;
    opt.wppl = wppl;
    opt.heading_cost = heading_cost == "ties" ? tasks::HeadingCost::Ties : tasks::HeadingCost::Turns;
    opt.record_actions = !out_file.empty();
    opt.budget = planner::Budget::time_ms(budget_ms);
    if (budget_expansions > 0) opt.budget.expansions = budget_expansions;
    // Progress: steps done, throughput so far, p99 latency so far.
    std::vector<double> lat, cpu;
    long done = 0;
    auto last = planner::Clock::now();
    if (!quiet && progress_s > 0)
      opt.on_step = [&](const StepRecord& s) {
        lat.push_back(s.planner_ms);
        cpu.push_back(s.planner_cpu_ms);
        done += s.completed;
        if (planner::ms_since(last) < progress_s * 1000 && s.t != steps) return;
        last = planner::Clock::now();
        std::cerr << "[" << pr.name << " " << solver << " " << budget_ms << "ms] step " << s.t << "/" << steps
                  << "  errands " << done << "  errandThroughput " << static_cast<double>(done) / s.t << "/step  p99 "
                  << summarize(lat).p99 << " ms (cpu " << summarize(cpu).p99 << " ms)" << std::endl;
      };

    LifelongExecResult xr;
    if (!executor_mode.empty() && opt.action_model != ActionModel::Grid4)
      throw planner::InputError("--executor runs grid4 plans; --action-model rotation has its own executor");
    if (!executor_mode.empty()) {
      exec.mode = executor_mode;
      for (const std::string& s : slow) {
        executor::Slowdown d;
        if (std::sscanf(s.c_str(), "%d:%lf", &d.agent, &d.factor) != 2)
          throw planner::InputError("--slow '" + s + "': expected AGENT:FACTOR");
        delays.slow.push_back(d);
      }
      for (const std::string& s : stuck) {
        executor::Stuck d;
        if (std::sscanf(s.c_str(), "%d:%lld:%lld", &d.agent, &d.at, &d.ticks) != 3)
          throw planner::InputError("--stuck '" + s + "': expected AGENT:AT:STEPS");
        delays.stuck.push_back(d);
      }
      if (std::string e = executor::check(exec); !e.empty()) throw planner::InputError("--" + e);
      if (std::string e = executor::check(delays, pr.team_size); !e.empty()) throw planner::InputError("--delay " + e);
      xr = run_lifelong_exec(g, starts, *tm, solver, seed, opt, delays, exec);
    } else if (delays.kind != "none" || !slow.empty() || !stuck.empty()) {
      throw planner::InputError("delay options need --executor lockstep|adg");
    } else {
      xr.life = run_lifelong(g, starts, *tm, solver, seed, opt);
    }
    const LifelongResult& r = xr.life;
    RunInfo info{problem_file, solver, mode, assigner, pr.team_size, budget_ms, seed};
    nlohmann::json j = out_file.empty() ? lifelong_log(info, r) : lorr_log(info, r, *tm, g);
    if (guidance != "none") j["guidance"] = guidance == "arrows" ? "arrows " + guidance_costs : guidance;
    if (ep.tf.on)
      j["trafficFlow"] = {{"active", tf_active}, {"contraflow", ep.tf.contraflow}, {"vertex", ep.tf.vertex}, {"refresh", ep.tf.refresh}};
    if (!executor_mode.empty())
      j["executor"] = {{"mode", exec.mode},
                       {"window", exec.window},
                       {"delayKind", delays.kind},
                       {"delayP", delays.p},
                       {"delayRate", delays.rate},
                       {"delayTicks", {delays.min_ticks, delays.max_ticks}},
                       {"commits", xr.exec.commits},
                       {"moves", xr.exec.moves},
                       {"dependencyWaits", xr.exec.dependency_waits},
                       {"lockstepWaits", xr.exec.lockstep_waits},
                       {"delayAgentTicks", xr.exec.delay_ticks},
                       {"maxTicksWithoutErrand", xr.max_gap}};
    if (pref) j["policy"] = policy_file;
    j["keepPriorities"] = !reset_priorities;
    add_task_fields(j, *tm);
    const int sig = planner::stop_signal();
    if (sig) j["interrupted"] = planner::signal_name(sig);
    if (!out_file.empty()) {
      planner::write_file(out_file, j.dump() + "\n");
    }
    for (const char* k : {"events", "plannerTimes", "start", "actualPaths", "plannerPaths", "tasks", "actualSchedule",
                          "plannerSchedule", "errors"})
      j.erase(k);
    std::cout << j.dump(2) << std::endl;
    if (r.planner_errors > 0) {
      std::cerr << "rtlacam-lifelong: invalid move: " << r.first_error << std::endl;
      return cli::kInvalidPlan;
    }
    if (sig) {
      std::cerr << "rtlacam-lifelong: stopped by " << planner::signal_name(sig) << " after " << r.steps << " steps"
                << (out_file.empty() ? std::string() : "; log complete in " + out_file) << std::endl;
      return cli::signal_exit(sig);
    }
    return cli::kOk;
  } catch (const planner::InputError& e) {
    std::cerr << "rtlacam-lifelong: " << e.what() << std::endl;
    return cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "rtlacam-lifelong: error: " << e.what() << std::endl;
    return cli::kRuntimeError;
  }
}
