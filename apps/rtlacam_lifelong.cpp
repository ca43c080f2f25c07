// rtlacam-lifelong: a lifelong run on a LoRR problem (no SUMO). Prints a summary JSON
// (the log without per-step lists); --out writes the full LoRR / PlanViz log; progress goes
// to stderr.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "cli.hpp"
#include "lifelong_cli.hpp"
#include "planner/error.hpp"
#include "planner/output_file.hpp"
#include "planner/stop_signal.hpp"
#include "tasks/lifelong_exec.hpp"
#include "tasks/lifelong_log.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_instance.hpp"

using namespace tasks;

int main(int argc, char** argv)
{
  CLI::App app{"Lifelong MAPF on a League of Robot Runners problem: task layer + real-time planner"};
  std::string problem_file, out_file, action_model = "grid4";
  int rotation_window = 8;
  bool no_heading_ties = false;
  std::string heading_cost = "turns";
  size_t max_dist_tables = 0;
  bool prefetch = true, bound_queries = true;
  bool skip_late_search = false;
  double expansion_deviations = 4;
  long steps = -1;
  double budget_ms = 100, progress_s = 2;
  uint64_t budget_expansions = 0;
  int agents = 0;
  bool quiet = false;
  cli::SolverCli sc;  // --solver, --seed, --policy and every solver's options
  cli::ExecCli xc;    // --executor and the delays
  cli::TaskCli tc;    // the task layer: --mode, --assigner, --queue-*, --parking, --urgency, --battery-*, ...
  app.add_option("--problem", problem_file, "LoRR problem JSON")->required();
  app.add_option("--steps", steps, "steps to simulate (default: the instance's simulation_time)")
      ->check(cli::non_negative());  // -5 read as unset: "no simulation_time.json entry"
  app.add_option("--agents", agents, "use only the first N agents of the team (default: teamSize)")->check(cli::positive());
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
      ->check(cli::non_negative())
      ->capture_default_str();
  app.add_option("--max-dist-tables", max_dist_tables,
                 "distance tables kept (LRU; tables in use are kept beyond it); 0 = 2 x agents + 256");
  app.add_option("--budget-ms", budget_ms, "planning budget per step (wall clock)")
      ->check(cli::finite_range(0, 3.6e6))
      ->capture_default_str();
  app.add_option("--budget-expansions", budget_expansions, "also limit LaCAM expansions (wppl: LNS iterations) per step (deterministic); 0 = none");
  app.add_option("--action-model", action_model, "grid4 (4-connected moves) | rotation (LoRR MAPF_T: heading, a step per quarter turn)")
      ->check(CLI::IsMember({"grid4", "rotation"}))
      ->capture_default_str();
  app.add_option("--rotation-window", rotation_window, "rotation: plan steps the planner may run ahead of the slowest robot")
      ->check(cli::positive())
      ->capture_default_str();
  app.add_flag("--no-heading-ties", no_heading_ties, "rotation: PIBT breaks distance ties at random, not by turns");
  app.add_option("--heading-cost", heading_cost,
                 "rotation: PIBT's move order: turns (rotation-aware cost in steps) or ties (distance, ties by turns)")
      ->check(CLI::IsMember({"turns", "ties"}));
  app.add_option("--out", out_file, "write the full LoRR / PlanViz log (paths, events, tasks) here");
  app.add_option("--progress-s", progress_s, "seconds between progress lines on stderr; 0 = none")->capture_default_str();
  app.add_flag("--quiet", quiet, "no progress lines");
  tc.bind(app);
  sc.bind(app);
  xc.bind(app);
  cli::add_version(app, "rtlacam-lifelong");
  RTLACAM_PARSE(app, argc, argv);
  planner::install_stop_handlers();  // SIGINT / SIGTERM: stop stepping, write the log, exit 130 / 143

  try {
    const LorrInstance in = load_lorr_instance(problem_file, agents, "--agents ");
    const LorrProblem& pr = in.problem;
    const planner::Graph g = tc.graph(in.g, *in.tasks);
    const planner::Config& starts = in.starts;
    const std::shared_ptr<const TaskFile>& file = in.tasks;
    if (steps < 0) steps = pr.simulation_time;
    if (steps < 0) throw planner::input_error(problem_file, 0, "no simulation_time.json entry for this problem: pass --steps");

    tc.default_in_line(sc.solver);
    const std::unique_ptr<TaskManager> tm = tc.make(pr, g, file);

    LifelongOptions opt;
    // Naming a rotation solver is enough (as planner.solver in the YAML and Python's lifelong):
    // the action model follows; --action-model grid4 with it stays an error.
    if (!app.count("--action-model") && planner::plans_rotation(planner::parse_solver(sc.solver))) action_model = "rotation";
    sc.apply(app, g, starts.size(), action_model == "rotation", opt.solver);
    opt.prefetch = prefetch;
    opt.max_dist_tables = max_dist_tables;
    opt.bound_queries = bound_queries;
    opt.skip_late_search = skip_late_search;
    opt.expansion_deviations = expansion_deviations;
    opt.steps = steps;
    opt.action_model = parse_action_model(action_model);
    opt.rotation_window = rotation_window;
    opt.heading_ties = !no_heading_ties;
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
        std::cerr << "[" << pr.name << " " << sc.solver << " " << budget_ms << "ms] step " << s.t << "/" << steps
                  << "  errands " << done << "  errandThroughput " << static_cast<double>(done) / s.t << "/step  p99 "
                  << summarize(lat).p99 << " ms (cpu " << summarize(cpu).p99 << " ms)" << std::endl;
      };

    xc.apply(pr.team_size, opt);
    if (opt.graph_execution && opt.action_model == tasks::ActionModel::Rotation &&
        !planner::plans_rotation(planner::parse_solver(sc.solver)))
      throw planner::InputError("--executor " + opt.exec.mode + " with --action-model rotation needs a rotation solver (pibt-rot, epibt, wppl): " +
                                sc.solver + "'s cell plan runs on the rotation executor");
    LifelongExecResult xr;
    if (opt.graph_execution)
      xr = run_lifelong_exec(g, starts, *tm, sc.solver, sc.seed, opt, opt.delays, opt.exec);
    else
      xr.life = run_lifelong(g, starts, *tm, sc.solver, sc.seed, opt);
    const LifelongResult& r = xr.life;
    RunInfo info{problem_file, sc.solver, tc.mode, tc.assigner, pr.team_size, budget_ms, sc.seed};
    nlohmann::json j = out_file.empty() ? lifelong_log(info, r) : lorr_log(info, r, *tm, g);
    sc.describe(j);
    if (opt.graph_execution)
      j["executor"] = {{"mode", opt.exec.mode},
                       {"window", opt.exec.window},
                       {"delayKind", opt.delays.kind},
                       {"delayP", opt.delays.p},
                       {"delayRate", opt.delays.rate},
                       {"delayTicks", {opt.delays.min_ticks, opt.delays.max_ticks}},
                       {"commits", xr.exec.commits},
                       {"moves", xr.exec.moves},
                       {"dependencyWaits", xr.exec.dependency_waits},
                       {"lockstepWaits", xr.exec.lockstep_waits},
                       {"delayAgentTicks", xr.exec.delay_ticks},
                       {"turnTicks", xr.exec.turn_ticks},
                       {"maxTicksWithoutErrand", xr.max_gap}};
    add_task_fields(j, *tm);
    add_stuck_fields(j, r);
    if (const std::string w = stuck_warning(r); !w.empty()) std::cerr << "rtlacam-lifelong: " << w << std::endl;
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
