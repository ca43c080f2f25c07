#include "controller/controller.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "controller/commander.hpp"
#include "controller/fleet.hpp"
#include "controller/lifelong.hpp"
#include "controller/sumo_error.hpp"
#include "controller/sumo_options.hpp"
#include "gridify/gridifier.hpp"
#include "planner/error.hpp"
#include "planner/naive_rt_lacam.hpp"
#include "planner/pibt_planner.hpp"
#include "planner/plan_io.hpp"
#include "planner/rt_lacam.hpp"
#include "planner/validator.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"
#include "tasks/lifelong_goal.hpp"
#include "tasks/lifelong_log.hpp"
#include "tasks/lifelong_runner.hpp"

namespace controller {

namespace fs = std::filesystem;
using planner::Clock;
using planner::ms_since;

std::unique_ptr<planner::RealtimePlanner> make_planner(const PlannerSection& p, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::ActionPreference* pref, planner::GoalTest test)
{
  planner::LacamOptions opt;
  opt.swap = p.swap;
  opt.seed = p.seed;
  opt.keep_priorities = p.keep_priorities;
  opt.refine = p.refine;
  if (p.solver == "naive") return std::make_unique<planner::NaiveRtLacam>(g, starts, goals, opt, pref, std::move(test));
  if (p.solver == "pibt" || p.solver == "cspibt") {
    if (p.solver == "cspibt" && !pref) throw std::invalid_argument("solver cspibt needs a policy (planner.policy)");
    return std::make_unique<planner::PibtPlanner>(g, starts, goals, opt, pref, std::move(test));
  }
  return std::make_unique<planner::RtLacam>(g, starts, goals, opt, pref, std::move(test));
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
  m.policy = cfg_.planner.policy;
  m.tick_s = cfg_.run.tick_s;
  m.step_length = cfg_.sumo.step_length;
  m.budget_ms = cfg_.planner.budget_ms;
  m.mode = cfg_.tasks.mode;
  const bool lifelong = cfg_.tasks.lifelong();
  if (lifelong) m.assignment = cfg_.tasks.assignment;

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
  if (!lifelong) m.soc_lb = ins.soc_lower_bound(g);
  // Lifelong: the task stream (its errors are config errors too).
  std::unique_ptr<tasks::TaskManager> tm;
  if (lifelong) tm = make_task_manager(cfg_, map_, make_task_file(cfg_, map_));
  // The learned policy (CS-PIBT move order). Its observations are grid windows: the net
  // must be an axis-aligned lattice (gridify then attaches the grid view). The planner
  // tells it the goals (ActionPreference::set_goals), so it starts with none.
  policy::Model model;
  std::unique_ptr<policy::PolicyPreference> pref;
  if (!cfg_.planner.policy.empty()) {
    if (!g.is_grid())
      throw ConfigError(cfg_.path + ": planner.policy: needs a net whose cells lie on a lattice ('" + cfg_.sumo.net +
                        "' does not: its observations are grid windows)");
    try {
      model = policy::load_weights(cfg_.planner.policy);
    } catch (const planner::InputError& e) {
      throw ConfigError(cfg_.path + ": planner.policy: " + e.what());
    }
    pref = std::make_unique<policy::PolicyPreference>(g, model, planner::Config{});
  }

  const std::string dir = cfg_.output.dir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw ConfigError(cfg_.path + ": output.dir: cannot create '" + dir + "'");
  double max_spacing = 0;
  for (const gridify::Aisle& a : map_.aisles) max_spacing = std::max(max_spacing, a.spacing);

  std::unique_ptr<SumoBackend> sumo = make_backend(cfg_.run);
  m.backend = sumo->name();
  Commander cmd(map_, *sumo, cfg_.run.tick_s);
  tasks::LifelongResult life;  // lifelong bookkeeping for the log
  planner::Config goals = ins.goals;
  planner::GoalTest goal_test;
  auto setup0 = Clock::now();
  if (tm) {
    // Duplicate goals are normal here (two AGVs sent to one station): the lifelong goal
    // test ("some AGV not yet arrived stands on its goal") never needs distinct goals.
    tm->start(ins.starts);
    goals = tm->goals();
    goal_test = tasks::lifelong_goal_test(*tm, ins.starts);
  }
  std::unique_ptr<planner::RealtimePlanner> p = make_planner(cfg_.planner, g, ins.starts, goals, pref.get(), goal_test);
  if (tm) {
    // Thousands of goal cells over a run: keep the tables in use plus a few hundred recent.
    p->set_max_dist_tables(2 * ins.starts.size() + 256);
    life.setup_ms = ms_since(setup0);
    life.epochs = 1;
  }
  planner::Validator val(g, ins.starts, goals);
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
  double epoch_ms = 0;  // lifelong: planner time of a new epoch, charged to the next tick
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
      if (!tm && p->at_goal()) {
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
      const double tick_planner_ms = plan_in_tick + epoch_ms;
      epoch_ms = 0;

      t0 = Clock::now();
      cmd.verify(next, tolerance);
      control.push_back(ctl + ms_since(t0));
      cur = next;
      plan_.push_back(cur);
      ++m.ticks;
      m.makespan = val.steps();  // executed ticks only (a tick cut short by an error is not)
      m.soc = val.sum_of_costs();

      if (tm) {
        // The tick boundary of the task layer: the AGVs stand exactly on `cur` (verified
        // above) and the planner has committed to it. Errands completed at the end of tick
        // t (1-based) start a new epoch: new goals, a fresh tree rooted at `cur`, and one
        // search slice so the next tick has a first move (a fresh tree's only node is the
        // root: without it every AGV would wait one tick after each completion).
        life.planner_ms.push_back(tick_planner_ms);
        t0 = Clock::now();
        const std::vector<tasks::Event> ev = tasks::advance_epoch(*tm, *p, m.ticks);
        if (!ev.empty()) {
          val.set_goals(tm->goals());
          p->search(budget);
          ++life.epochs;
          life.events.insert(life.events.end(), ev.begin(), ev.end());
          epoch_ms = ms_since(t0);
        } else {
          life.task_ms += ms_since(t0);
        }
        m.errands_finished = tm->errands_finished();
        m.tasks_finished = tm->tasks_finished();
      }

      if (cfg_.run.progress_s > 0 && std::chrono::duration<double>(Clock::now() - last_progress).count() >= cfg_.run.progress_s) {
        last_progress = Clock::now();
        const double wall = ms_since(wall0) / 1000;
        if (tm) {
          std::fprintf(stderr,
                       "[rtlacam-sumo] tick %lld/%lld  errands %lld (%.3f/tick)  tasks %lld (%.3f/tick)  planner p99 %.2f "
                       "ms/tick  wall %.1f s (%.0fx real time)\n",
                       m.ticks, cfg_.run.max_ticks, m.errands_finished, m.errand_throughput(), m.tasks_finished,
                       m.throughput(), tasks::summarize(life.planner_ms).p99, wall,
                       wall > 0 ? m.ticks * cfg_.run.tick_s / wall : 0.0);
        } else {
          int at_goal = 0;
          for (int i = 0; i < ins.num_agents(); ++i) at_goal += cur[i] == ins.goals[i];
          std::fprintf(stderr, "[rtlacam-sumo] tick %lld/%lld  at goal %d/%d  sim %.1f s  wall %.1f s (%.0fx real time)\n",
                       m.ticks, cfg_.run.max_ticks, at_goal, ins.num_agents(), m.ticks * cfg_.run.tick_s, wall,
                       wall > 0 ? m.ticks * cfg_.run.tick_s / wall : 0.0);
        }
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

  if (tm) {
    m.epochs = life.epochs;
    life.steps = m.ticks;
    life.errands_finished = m.errands_finished;
    life.tasks_finished = m.tasks_finished;
    life.expansions = m.expansions;
    life.wall_ms = m.wall_s * 1000;
    life.planner_errors = m.violations;
    if (m.violations > 0) life.first_error = m.error;
    tasks::RunInfo info;
    info.problem = cfg_.path;
    info.solver = p->name();
    info.mode = cfg_.tasks.assignment;
    info.assigner = cfg_.tasks.assigner;
    info.team_size = m.agents;
    info.budget_ms = cfg_.planner.budget_ms;
    info.seed = cfg_.tasks.seed;
    nlohmann::json j = tasks::lifelong_log(info, life);
    if (tm) tasks::add_task_fields(j, *tm);
    j["tickS"] = cfg_.run.tick_s;
    j["backend"] = m.backend;
    j["expansionsPerSumoStep"] = cfg_.planner.expansions;
    j["taskCount"] = tm ? static_cast<long long>(cfg_.tasks.random_tasks ? cfg_.tasks.count : cfg_.tasks.list.size()) : 0;
    if (!m.error.empty()) j["error"] = m.error;
    std::ofstream(dir + "/" + cfg_.tasks.log) << j.dump(2) << '\n';
  }
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
    planner::write_plan(out, g, ins.starts, tm ? tm->goals() : ins.goals, plan_, h);
  }
  return m;
}

}  // namespace controller
