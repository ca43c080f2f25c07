#include "controller/controller.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "controller/commander.hpp"
#include "controller/fleet.hpp"
#include "controller/sumo_error.hpp"
#include "controller/sumo_options.hpp"
#include "gridify/gridifier.hpp"
#include "planner/error.hpp"
#include "planner/naive_rt_lacam.hpp"
#include "planner/pibt_planner.hpp"
#include "planner/plan_io.hpp"
#include "planner/rt_lacam.hpp"
#include "planner/validator.hpp"

namespace controller {

namespace fs = std::filesystem;
using planner::Clock;
using planner::ms_since;

std::unique_ptr<planner::RealtimePlanner> make_planner(const PlannerSection& p, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals)
{
  planner::LacamOptions opt;
  opt.swap = p.swap;
  opt.seed = p.seed;
  if (p.solver == "naive") return std::make_unique<planner::NaiveRtLacam>(g, starts, goals, opt);
  if (p.solver == "pibt") return std::make_unique<planner::PibtPlanner>(g, starts, goals, opt);
  return std::make_unique<planner::RtLacam>(g, starts, goals, opt);
}

std::unique_ptr<SumoBackend> make_backend(const RunSection& r)
{
  if (r.gui) return make_traci_backend("sumo-gui", r.port);
  if (r.backend == "traci") return make_traci_backend("sumo", r.port);
  return make_libsumo_backend();
}

namespace {

std::string join_ids(const std::vector<std::string>& ids)
{
  std::string s;
  for (size_t i = 0; i < ids.size() && i < 5; ++i) s += (i ? ", " : "") + ids[i];
  if (ids.size() > 5) s += ", ... (" + std::to_string(ids.size()) + " in all)";
  return s;
}

// SUMO must never act on its own: after each step, nothing arrived, teleported or collided.
void check_events(SumoBackend& sumo, double t)
{
  char when[64];
  std::snprintf(when, sizeof when, "t=%.3f s: ", t);
  std::vector<std::string> ids = sumo.arrived();
  if (!ids.empty())
    throw ControlError(when + std::string("AGV(s) left the network: ") + join_ids(ids) +
                       " (arrived at a route end or removed behind the controller's back)");
  ids = sumo.teleported();
  if (!ids.empty()) throw ControlError(when + std::string("SUMO teleported AGV(s): ") + join_ids(ids));
  ids = sumo.colliding();
  if (!ids.empty()) throw ControlError(when + std::string("SUMO reports colliding AGV(s): ") + join_ids(ids));
}

}  // namespace

Metrics Controller::run()
{
  const auto wall0 = Clock::now();
  Metrics m;
  m.config = cfg_.path;
  m.net = cfg_.sumo.net;
  m.solver = cfg_.planner.solver;
  m.tick_s = cfg_.run.tick_s;
  m.step_length = cfg_.sumo.step_length;
  m.budget_ms = cfg_.planner.budget_ms;

  // Everything that can be wrong with the input fails here, before SUMO starts.
  gridify::GridifyOptions go;
  go.cell_length = cfg_.grid.cell_length;
  go.tolerance = cfg_.grid.tolerance;
  go.snap = cfg_.grid.snap;
  go.drop_one_way = cfg_.grid.drop_one_way;
  go.additional = cfg_.sumo.additional;
  try {
    map_ = gridify::gridify(cfg_.sumo.net, go);
  } catch (const planner::InputError& e) {
    throw ConfigError(cfg_.path + ": sumo.net: " + e.what());
  }
  const planner::Instance ins = make_instance(cfg_, map_);
  const planner::Graph& g = map_.graph;
  m.agents = ins.num_agents();
  m.cells = g.size();
  m.soc_lb = ins.soc_lower_bound(g);

  const std::string dir = cfg_.output.dir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw ConfigError(cfg_.path + ": output.dir: cannot create '" + dir + "'");
  double max_spacing = 0;
  for (const gridify::Aisle& a : map_.aisles) max_spacing = std::max(max_spacing, a.spacing);

  std::unique_ptr<SumoBackend> sumo = make_backend(cfg_.run);
  m.backend = sumo->name();
  Commander cmd(map_, *sumo, cfg_.run.tick_s);
  std::unique_ptr<planner::RealtimePlanner> p = make_planner(cfg_.planner, g, ins.starts, ins.goals);
  planner::Validator val(g, ins.starts, ins.goals);
  const planner::Budget budget{cfg_.planner.budget_ms > 0 ? cfg_.planner.budget_ms : planner::Budget{}.ms,
                               cfg_.planner.expansions > 0 ? cfg_.planner.expansions : planner::Budget{}.expansions};
  const int k = cfg_.steps_per_tick();
  std::vector<double> plan_step, plan_tick, sumo_step, control;
  plan_step.reserve(static_cast<size_t>(std::min<long long>(cfg_.run.max_ticks, 100000)) * k);
  double plan_in_tick = 0;

  // One SUMO step with the planner's share of thinking before it.
  auto step_once = [&] {
    auto t0 = Clock::now();
    p->search(budget);
    const double ms = ms_since(t0);
    plan_step.push_back(ms);
    plan_in_tick += ms;
    t0 = Clock::now();
    sumo->step();
    sumo_step.push_back(ms_since(t0));
    check_events(*sumo, sumo->time());
  };

  plan_ = {ins.starts};
  planner::Config cur = ins.starts;
  auto last_progress = Clock::now();
  auto loop0 = Clock::now();  // start of the tick loop (after start-up and insertion)
  try {
    sumo->start(sumo_args(cfg_, dir, write_vtype_file(cfg_, dir, max_spacing), cmd.needs_ignore_route_errors()));
    cmd.insert(ins.starts);
    step_once();  // inserts the AGVs
    const std::vector<std::string> waiting = sumo->pending();
    if (!waiting.empty()) throw ControlError("SUMO could not insert AGV(s) on their start cells: " + join_ids(waiting));
    cmd.verify(cur, tolerance);

    loop0 = Clock::now();
    for (;;) {
      if (p->at_goal()) {
        m.solved = true;
        break;
      }
      if (m.ticks >= cfg_.run.max_ticks) break;
      if (on_tick) on_tick(m.ticks, *sumo);

      auto t0 = Clock::now();
      const planner::Config next = p->next();
      p->commit();
      if (!val.step(next)) throw ControlError("tick " + std::to_string(m.ticks) + ": invalid MAPF step: " + val.error());
      cmd.command(cur, next);
      double ctl = ms_since(t0);

      plan_in_tick = 0;
      for (int s = 0; s < k; ++s) {
        if (s == k - 1) sumo->request_poses();  // verify() reads them after this step
        step_once();
      }
      plan_tick.push_back(plan_in_tick);

      t0 = Clock::now();
      cmd.verify(next, tolerance);
      control.push_back(ctl + ms_since(t0));
      cur = next;
      plan_.push_back(cur);
      ++m.ticks;
      m.makespan = val.steps();  // executed ticks only (a tick cut short by an error is not)
      m.soc = val.sum_of_costs();

      if (cfg_.run.progress_s > 0 && std::chrono::duration<double>(Clock::now() - last_progress).count() >= cfg_.run.progress_s) {
        last_progress = Clock::now();
        int at_goal = 0;
        for (int i = 0; i < ins.num_agents(); ++i) at_goal += cur[i] == ins.goals[i];
        const double wall = ms_since(wall0) / 1000;
        std::fprintf(stderr, "[rtlacam-sumo] tick %lld/%lld  at goal %d/%d  sim %.1f s  wall %.1f s (%.0fx real time)\n",
                     m.ticks, cfg_.run.max_ticks, at_goal, ins.num_agents(), m.ticks * cfg_.run.tick_s, wall,
                     wall > 0 ? m.ticks * cfg_.run.tick_s / wall : 0.0);
      }
    }
  } catch (const ControlError& e) {
    m.error = e.what();
    ++m.violations;
  } catch (const SumoError& e) {
    m.error = e.what();
  } catch (const std::exception& e) {
    m.error = std::string("controller: ") + e.what();
  }
  if (m.error.empty()) {
    try {
      m.sim_s = sumo->time();
    } catch (const SumoError&) {
    }
  }
  m.loop_s = ms_since(loop0) / 1000;
  sumo->close();  // flushes SUMO's output files

  m.expansions = p->expansions();
  m.planner_ms_per_step = Latency::of(plan_step);
  m.planner_ms_per_tick = Latency::of(plan_tick);
  m.sumo_ms_per_step = Latency::of(sumo_step);
  m.control_ms_per_tick = Latency::of(control);
  m.commands = cmd.stats();
  m.wall_s = ms_since(wall0) / 1000;
  if (m.sim_s == 0) m.sim_s = m.ticks * cfg_.run.tick_s;

  std::ofstream(dir + "/metrics.json") << m.to_json().dump(2) << '\n';
  if (cfg_.output.plan) {
    planner::PlanHeader h;
    h.map_file = cfg_.sumo.net;
    h.solver = p->name();
    h.solved = m.solved;
    h.soc = m.soc;
    h.soc_lb = m.soc_lb;
    h.makespan = m.makespan;
    h.comp_time_ms = m.planner_ms_per_step.mean * m.planner_ms_per_step.count;
    h.extra = {{"backend", m.backend}, {"ticks", std::to_string(m.ticks)}, {"error", m.error}};
    std::ofstream out(dir + "/plan.txt");
    planner::write_plan(out, g, ins.starts, ins.goals, plan_, h);
  }
  return m;
}

}  // namespace controller
