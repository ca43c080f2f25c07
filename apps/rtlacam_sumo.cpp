// rtlacam-sumo: a SUMO warehouse run in which RT-LaCAM drives every AGV cell by cell.
// Exit codes (apps/cli.hpp): 0 every AGV reached its goal (lifelong: run.max_ticks ran
// clean); 2 bad config, net or command line; 3 an invalid MAPF step or AGVs in conflict
// (overlap, SUMO collision); 4 a one-shot run where run.max_ticks ended first, or an
// instance proven unsolvable; 1 any other error (SUMO failure, an AGV vanished, a file
// that could not be written); 130 / 143 SIGINT / SIGTERM -- metrics.json is written in
// every case but bad input.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "cli.hpp"
#include "controller/controller.hpp"
#include "planner/error.hpp"
#include "planner/solver.hpp"
#include "planner/stop_signal.hpp"

using namespace controller;

int main(int argc, char** argv)
{
  CLI::App app{"Run a SUMO warehouse scenario with RT-LaCAM commanding every AGV"};
  std::string path, backend, solver, out, policy_file, executor;
  bool gui = false;
  long long max_ticks = 0;
  int port = 0, order = 0;
  app.add_option("config", path, "scenario YAML (config/<scenario>.yaml)")->required();
  app.add_flag("--gui", gui, "watch it live in sumo-gui (through TraCI)");
  app.add_option("--backend", backend, "libsumo (embedded, default) or traci")->check(CLI::IsMember({"libsumo", "traci"}));
  app.add_option("--solver", solver, "override planner.solver: " + planner::solver_names(true))
      ->check(CLI::IsMember(planner::solver_list(true)));
  app.add_option("--executor", executor, "override run.executor: lockstep | adg | adg-follow")
      ->check(CLI::IsMember({"lockstep", "adg", "adg-follow"}));
  app.add_option("--policy", policy_file, "override planner.policy: learned policy weights (PIBT tries moves in its order)")
      ->check(CLI::ExistingFile);
  app.add_option("--port", port, "traci: connect to a SUMO already listening on this port (sumo --remote-port)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--order", order, "with --port: this client's TraCI order in a SUMO of several clients (sumo --num-clients)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--max-ticks", max_ticks, "override run.max_ticks")->check(cli::positive());
  app.add_option("--out", out, "override output.dir");
  cli::add_version(app, "rtlacam-sumo");
  RTLACAM_PARSE(app, argc, argv);
  planner::install_stop_handlers();  // SIGINT / SIGTERM end the run through its normal end

  try {
    Config cfg = load_config(path);
    if (gui) cfg.run.gui = true;
    if (!backend.empty()) cfg.run.backend = backend;
    if (!solver.empty()) cfg.planner.solver = solver;
    if (!policy_file.empty()) cfg.planner.policy = policy_file;
    if (!executor.empty()) cfg.run.executor = executor;
    check_solver(cfg);
    if (port > 0) {
      cfg.run.port = port;
      if (backend.empty()) cfg.run.backend = "traci";
    }
    if (order > 0) {
      if (port == 0 && cfg.run.port == 0) throw ConfigError("--order: only with --port (or run.port)");
      cfg.run.order = order;
    }
    if (max_ticks > 0) cfg.run.max_ticks = max_ticks;
    if (!out.empty()) cfg.output.dir = out;

    Controller c(cfg);
    Metrics m = c.run();
    if (!m.policy.empty()) m.solver += "+policy";
    if (cfg.tasks.lifelong())
      std::printf("%s: %d AGVs, %s via %s, lifelong %s: %lld ticks, %lld errands (%.3f/tick), %lld tasks (%.3f/tick), "
                  "%lld epochs; log %s/%s\n",
                  path.c_str(), m.agents, m.solver.c_str(), m.backend.c_str(), m.assignment.c_str(), m.ticks,
                  m.errands_finished, m.errand_throughput(), m.tasks_finished, m.throughput(), m.epochs,
                  cfg.output.dir.c_str(), cfg.tasks.log.c_str());
    else
      std::printf("%s: %d AGVs, %s via %s: %s after %lld ticks (makespan %lld, soc %lld, lb %lld)\n", path.c_str(),
                  m.agents, m.solver.c_str(), m.backend.c_str(),
                  m.solved ? "all at goal" : m.unsolvable ? "unsolvable (the search proved no solution)" : "NOT solved", m.ticks,
                  m.makespan, m.soc, m.soc_lb);
    // Microseconds: once the goal is found the planner only follows its path, so most SUMO
    // steps cost well under a millisecond and "0.000 ms" would read as "not running".
    std::printf("  planner us/SUMO step mean %.1f p50 %.1f p99 %.1f max %.1f; sumo ms/step mean %.3f; wall %.2f s (%.0fx real time)\n",
                1e3 * m.planner_ms_per_step.mean, 1e3 * m.planner_ms_per_step.p50, 1e3 * m.planner_ms_per_step.p99,
                1e3 * m.planner_ms_per_step.max, m.sumo_ms_per_step.mean, m.wall_s, m.wall_s > 0 ? m.sim_s / m.wall_s : 0.0);
    const Metrics::PerSimSecond ps = m.per_sim_second();
    std::printf("  per simulated second: wall %.2f ms = sumo %.2f + controller %.2f (planner %.2f, commands/checks %.2f); "
                "controller/sumo %.2f\n",
                ps.wall_ms, ps.sumo_ms, ps.controller_ms, ps.planner_ms, ps.control_ms, ps.ratio);
    std::printf("  commands %lld, re-syncs %lld, max position error %.3g m, violations %lld; outputs in %s\n",
                m.commands.total(), m.commands.resyncs, m.commands.max_error, m.violations, cfg.output.dir.c_str());
    if (!m.error.empty()) {
      std::cerr << "error: " << m.error << '\n';
      return m.violations > 0 ? cli::kInvalidPlan : cli::kRuntimeError;
    }
    if (m.signal) {
      std::cerr << "rtlacam-sumo: stopped by " << planner::signal_name(m.signal) << " after " << m.ticks
                << " ticks; outputs complete in " << cfg.output.dir << '\n';
      return cli::signal_exit(m.signal);
    }
    if (m.unsolvable)
      std::cerr << "rtlacam-sumo: unsolvable: the search proved that no plan brings every AGV to its goal (stopped after "
                << m.ticks << " ticks)\n";
    return m.solved || cfg.tasks.lifelong() ? cli::kOk : cli::kUnsolved;
  } catch (const ConfigError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return cli::kBadInput;
  } catch (const planner::InputError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return cli::kRuntimeError;
  }
}
