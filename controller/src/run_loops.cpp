// The two tick loops of Run (run.hpp): lockstep (scheme S) and adg (executor/ + Driver),
// and the final phase writing the outputs.
#include <algorithm>
#include <cmath>
#include <functional>

#include "controller/bound.hpp"
#include "controller/sumo_error.hpp"
#include "controller/sumo_options.hpp"
#include "planner/output_file.hpp"
#include "planner/plan_io.hpp"
#include "planner/rotation/rotation_planner.hpp"
#include "run.hpp"
#include "tasks/action_model.hpp"
#include "tasks/lifelong_log.hpp"

namespace controller {

using planner::Clock;
using planner::ms_since;

// Lockstep: one committed configuration per tick, all AGVs together. With delays the whole
// fleet waits while a mover is stopped, and a step with a slowed mover is stretched over
// ceil(1 / factor) ticks for everybody ("all wait for the slowest").
void Run::loop_lockstep()
{
  planner::Config cur = ins_.starts;
  planner::Config next;  // committed, not yet executed
  // Rotation solvers: next's actions (F, R, C, W); a turn takes fleet.turn_s, so a tick
  // with one lasts ceil(turn_s / tick_s) ticks for everybody (all wait for the slowest).
  planner::RotationPlanner* rot = p_->rotation();
  std::string acts;
  const int turn_ticks = std::max(1, static_cast<int>(std::ceil(cfg_.fleet.turn_s / cfg_.run.tick_s - 1e-9)));
  for (;;) {
    // (An AGV waiting for a closed goal is not on its goal: rules.hpp.)
    if (!tm_ && p_->at_goal() && next.empty() &&
        std::find(waiting_.begin(), waiting_.end(), 1) == waiting_.end()) {
      m_.solved = true;
      break;
    }
    if (out_of_ticks()) break;
    if (c_.on_tick) c_.on_tick(m_.ticks, *sumo_);
    delays_->tick(m_.ticks);

    auto t0 = Clock::now();
    if (next.empty()) {
      if (rules_) {
        rules_tick(cur);  // closures that began or ended: a planner on the new graph
        rot = p_->rotation();
      }
      const double c0 = planner::thread_cpu_ms();
      next = p_->next();
      if (rot) {
        // The actions themselves: forward into the cell ahead, turns and waits in place.
        acts = rot->actions();
        const std::string bad = tasks::check_rotation_step(c_.map_.graph, p_->current(), rot->headings(), acts, next);
        if (!bad.empty()) throw ControlError("tick " + std::to_string(m_.ticks) + ": invalid rotation step: " + bad);
      }
      p_->commit();
      sb_.charge(0, planner::thread_cpu_ms() - c0);
      ++m_.commits;
      if (rules_ && cfg_.rules.enforce_zones) {
        // One AGV per zone (rules.hpp): entrants beyond one wait; a held step or a zone that
        // fills or empties restarts the planner at what is executed.
        const int held = rules_->admit(cur, next);
        m_.rules.zone_holds += held;
        if (held > 0 || rules_->blocked_zones(next) != zone_occ_) {
          rules_restart(next);
          rot = p_->rotation();
        }
      }
    }
    bool held = false;
    int ticks = 1;
    for (int i = 0; i < ins_.num_agents(); ++i) {
      if (next[i] == cur[i]) continue;
      held = held || delays_->stopped(i);
      ticks = std::max(ticks, delays_->move_ticks(i));
    }
    if (rot && !held) {
      // A slowed AGV turns slower too: its turn takes turn_ticks / factor.
      for (int i = 0; i < ins_.num_agents(); ++i)
        if (acts[static_cast<size_t>(i)] == 'R' || acts[static_cast<size_t>(i)] == 'C')
          ticks = std::max(ticks, static_cast<int>(std::ceil(turn_ticks / delays_->factor(i) - 1e-9)));
    }
    const planner::Config& to = held ? cur : next;
    int lane = ticks;
    if (!held && cfg_.run.lane_speeds) {
      // Lane speeds: the step lasts as many ticks as its slowest move needs on its lane.
      for (int i = 0; i < ins_.num_agents(); ++i)
        if (next[i] != cur[i]) lane = std::max(lane, cmd_->lane_ticks(i, cur[i], next[i]));
    }
    // A step stretched over several ticks that would end past run.max_ticks is not started:
    // the limit is the run's last tick (a 5-tick run took 6).
    if (m_.ticks + lane > cfg_.run.max_ticks) break;
    m_.lane_ticks += lane - ticks;
    ticks = lane;
    if (held) ++m_.lockstep_waits;
    if (!val_->step(to)) throw ControlError("tick " + std::to_string(m_.ticks) + ": invalid MAPF step: " + val_->error());
    cmd_->command(cur, to, ticks);
    if (rot && !held) {
      std::vector<double> factors(static_cast<size_t>(ins_.num_agents()));
      for (int i = 0; i < ins_.num_agents(); ++i) factors[static_cast<size_t>(i)] = delays_->factor(i);
      cmd_->turn(acts, factors);
    }
    show_lockstep(cur, next, held);
    double ctl = ms_since(t0);
    // This tick's outcome is known: its epoch start now, searched in the tick's steps.
    if (tm_ && epoch_early()) epoch_start(to, m_.ticks + ticks);

    std::vector<std::vector<planner::Vertex>> allowed(ins_.num_agents());
    for (int i = 0; i < ins_.num_agents(); ++i) allowed[i] = {cur[i], to[i]};
    plan_in_tick_ = 0;
    // The closed loop of cell moves (not turns; not while the fleet waits for a known stop):
    // a mover behind its schedule in SUMO -- braked or held by something the controller is
    // not told about -- paces the whole fleet to its progress (Commander::pace) until it
    // arrives, whole ticks more if need be, up to the tick limit. Without it the others drove
    // on into the cell it still held, and at the tick's end it was moved onto its cell
    // (session 47: 3 of 4 runs with outside stops ended in collisions). No deviation: the
    // commands of command() alone, as before.
    const bool watch = !rot && !held;
    const int nominal = k_ * ticks;
    bool paced = false;
    int s = 0;
    for (;; ++s) {
      if (s >= nominal) {
        if (!paced) break;
        if (s % k_ == 0 && (cmd_->progress(last_poses_) >= 1 - 1e-9 || m_.ticks + s / k_ >= cfg_.run.max_ticks ||
                            planner::stop_signal() != 0))
          break;
      }
      slice_ = s;
      if (rot) cmd_->orient();
      step(allowed, false);
      if (watch) {
        const double f = cmd_->progress(last_poses_);
        if (paced || f < std::min(1.0, (s + 1.0) / nominal) - 1e-6) {
          paced = true;
          cmd_->pace(last_poses_, std::min(1.0, f + 1.0 / nominal), cfg_.sumo.step_length);
        }
      }
    }
    if (paced) {
      ++m_.lockstep_paced;
      m_.lockstep_paced_ticks += s / k_ - ticks;
      ticks = s / k_;
    }
    plan_tick_.push_back(plan_in_tick_);
    const double tick_planner_ms = plan_in_tick_ + epoch_ms_;
    epoch_ms_ = 0;

    t0 = Clock::now();
    cmd_->verify(last_poses_, c_.tolerance);  // poses read after the tick's last step
    control_.push_back(ctl + ms_since(t0));
    cur = to;
    if (!held) next.clear();
    c_.plan_.push_back(cur);
    c_.plan_.settle(c_.plan_.size() - 1);  // lockstep: executed as committed
    m_.ticks += ticks;
    m_.makespan = val_->steps();  // executed steps only (a tick cut short by an error is not)
    m_.soc = val_->sum_of_costs();
    count_tick(cur, ticks);
    if (tm_) lifelong_tick(cur, tick_planner_ms);  // completions need moves: none while held
    progress_line(cur);
  }
}

// ADG: the planner commits up to run.window configurations ahead of the slowest AGV
// (never a pure wait), the Adg releases each AGV's moves, the Driver drives them.
void Run::loop_adg()
{
  executor::Adg adg(ins_.starts);
  DriveParams dp;
  dp.dt = cfg_.sumo.step_length;
  dp.accel = cfg_.fleet.vtype.accel;
  dp.decel = cfg_.fleet.vtype.decel;
  dp.max_speed = cfg_.fleet.vtype.max_speed;
  dp.follow = cfg_.run.executor == "adg-follow";
  dp.length = cfg_.fleet.vtype.length;
  dp.margin = cfg_.fleet.vtype.min_gap;
  dp.sure_travel = cfg_.run.relative_braking;
  dp.leader_decel = cfg_.run.leader_decel > 0 ? cfg_.run.leader_decel : dp.decel;
  dp.same_step_starts = cfg_.run.same_step_starts;
  dp.switch_passages = cfg_.run.switch_passages;
  dp.exact_chain = cfg_.run.chain_to_end;
  // Not with headings (rotation solvers, fleet.turn_s). The turns it seemed to interrupt
  // (session 31, ControllerRotationAdg.*) were turns still running when a lifelong run's tick
  // limit came -- the fcd ends mid-turn, the AGV at rest -- which the tests' fcd check now
  // accepts; with it on, every rotation test passes. It stays off there because it gained
  // nothing measurable with turns (small warehouse, fleet.turn_s 1, accel 2 / decel 4, planner
  // seeds 0-2: 258 ticks on against 256 off, s32).
  dp.gap_handover = cfg_.run.gap_handover && !cmd_->headings();
  dp.lane_speeds = cfg_.run.lane_speeds;
  Driver drv(*cmd_, adg, *delays_, dp);
  drv.set_goal_of([this](int i) { return p_->goals()[i]; });
  drv.set_trace(cfg_.sumo.outputs.fcd && !tm_);  // split_trace.txt beside the fcd (one-shot runs)
  if (rules_ && cfg_.rules.enforce_zones && !rules_->zones().empty()) drv.set_zones(&rules_->zones_of());
  // Rotation solvers: the plan's cells go to the ADG like a cell plan (its turns are waits
  // there), the Driver turns each AGV toward its next move (driver.hpp). The solver plans
  // one step per tick, at the tick's first SUMO step, with the tick's budget (as in
  // lockstep: it cannot spread a step's search over SUMO steps).
  planner::RotationPlanner* rot = p_->rotation();
  // Out-and-backs (executor/out_and_back.hpp): the commits pass through a lookahead of
  // run.out_and_back configurations, beyond the window, where an AGV's excursion
  // u -> ... -> u with u free meanwhile becomes waits on u. Lifelong: never through the AGV's
  // goal (an errand's visit); rules (only with run.out_and_back_rules): nobody else in u's
  // zone meanwhile either. Not rotation solvers: they commit one step per tick, and with the
  // cut small_warehouse_lifelong_agv under pibt-rot did fewer errands (session 34).
  executor::OutAndBackLimits limits;
  const bool plan = plan_mode();  // plan completions (run.hpp)
  // Plan completions: an errand done for planning stays a visit until it is executed.
  if (tm_)
    limits.keep = [this](int i, planner::Vertex v) {
      if (p_->goals()[i] == v) return true;
      for (const PlanCompletion& q : pending_)
        if (q.ev.agent == i && q.cell == v) return true;
      return false;
    };
  if (rules_ && cfg_.rules.enforce_zones && !rules_->zones().empty()) {
    const std::vector<std::vector<int>>* zone_of = &rules_->zones_of();
    limits.exclusive = [zone_of](planner::Vertex u, planner::Vertex w) {
      for (int z : (*zone_of)[u])
        for (int y : (*zone_of)[w])
          if (z == y) return true;
      return false;
    };
  }
  oab_ = std::make_unique<executor::OutAndBack>(ins_.starts, !rot && (!rules_ || cfg_.run.out_and_back_rules) ? cfg_.run.out_and_back : 0, cfg_.run.cut_loops,
                                                std::move(limits));
  // What leaves the lookahead is what is executed: validated, then to the ADG and the plan.
  auto hand_on = [&](bool all) {
    while (oab_->full() || (all && !oab_->empty())) {
      const planner::Config c = oab_->pop();
      if (!val_->step(c)) throw ControlError("tick " + std::to_string(m_.ticks) + ": invalid MAPF step: " + val_->error());
      adg.append(c);
      c_.plan_.push_back(c);
    }
  };
  auto executed = [&] {
    planner::Config c(ins_.num_agents());
    for (int i = 0; i < ins_.num_agents(); ++i) c[i] = adg.at(i);
    return c;
  };
  for (;;) {
    // (An AGV waiting for a closed goal is not on its goal: rules.hpp.)
    if (!tm_ && p_->at_goal() && adg.done() && oab_->empty() && std::find(waiting_.begin(), waiting_.end(), 1) == waiting_.end()) {
      m_.solved = true;
      break;
    }
    if (out_of_ticks()) break;
    if (c_.on_tick) c_.on_tick(m_.ticks, *sumo_);
    delays_->tick(m_.ticks);
    plan_in_tick_ = 0;
    if (rules_) {  // closures that began or ended, zones to route around: a replan (rules.hpp)
      const auto t0 = Clock::now();
      const double c0 = planner::thread_cpu_ms();
      rules_tick_adg(adg, drv);
      rot = p_->rotation();  // a replan built a new planner
      sb_.charge(0, planner::thread_cpu_ms() - c0);
      plan_in_tick_ += ms_since(t0);
    }
    double ctl = 0;
    for (int s = 0; s < k_; ++s) {
      slice_ = s;
      auto t0 = Clock::now();
      // Keep the window full. Commits never get ahead of what the ADG honours: any valid
      // plan is honoured, so the window only bounds how far the plan runs ahead. With
      // run.drain D < W the planner searches on until fewer than D are left, then refills.
      // (Immobile AGVs aside: stuck_replan.hpp.)
      auto progress = [&] { return stuck_ ? stuck_->min_progress(adg) : adg.min_progress(); };
      const int drain = cfg_.run.drain > 0 ? cfg_.run.drain : cfg_.run.window;
      const bool refill = adg.steps() - progress() < drain;
      int commits = 0;
      while (refill && adg.steps() - progress() < cfg_.run.window && !p_->at_goal() && !(rot && (s > 0 || commits > 0))) {
        const double c0 = planner::thread_cpu_ms();
        const planner::Config next = p_->next();
        // The search has nothing beyond the root yet (a rotation step of turns only is a step).
        const bool none = !rot && next == p_->current();
        if (rot) {
          // The actions themselves, checked as in lockstep (forward into the cell ahead).
          const std::string bad = tasks::check_rotation_step(c_.map_.graph, p_->current(), rot->headings(), rot->actions(), next);
          if (!bad.empty()) throw ControlError("tick " + std::to_string(m_.ticks) + ": invalid rotation step: " + bad);
        }
        if (!none) p_->commit();
        sb_.charge(0, planner::thread_cpu_ms() - c0);
        if (none) break;
        ++commits;
        ++m_.commits;
        oab_->push(next);
        hand_on(false);
        if (plan) plan_update(next, adg.steps() + static_cast<long long>(oab_->size()));
      }
      // All committed (the goals), or the ADG ran dry while the planner found nothing new:
      // what the lookahead holds goes on.
      if (p_->at_goal() || adg.steps() == progress()) hand_on(true);
      // Steps every AGV has finished are final: no replan rewrites them.
      settle(c_.plan_.size() - 1 - static_cast<size_t>(adg.steps()) + static_cast<size_t>(adg.min_progress()));
      const double commit_ms = ms_since(t0);
      plan_in_tick_ += commit_ms;
      t0 = Clock::now();
      drv.before_step();
      if (cmd_->headings()) {
        const std::vector<uint8_t> hold = drv.stopped();
        cmd_->orient(&hold);  // turns animate; AGVs facing off their lane are held at their angle
      }
      show_adg(adg);  // what each AGV does in this step
      const double before_ms = ms_since(t0);
      try {
        step(drv.allowed(), true, drv.groups());
      } catch (const ControlError& e) {
        const auto [a, b] = safety_->last_overlap();
        if (a < 0) throw;
        throw ControlError(std::string(e.what()) + "; " + drv.describe(a) + "; " + drv.describe(b));
      }
      t0 = Clock::now();
      drv.after_step(last_poses_);
      const double c1 = planner::thread_cpu_ms();
      stuck_step(adg, drv);
      sb_.charge(0, planner::thread_cpu_ms() - c1);  // a replan is planner work  // stuck AGVs: replan around them (stuck_replan.hpp)
      ctl += before_ms + ms_since(t0);
      exec_step_.back() += before_ms + ms_since(t0);
    }
    plan_tick_.push_back(plan_in_tick_);
    control_.push_back(ctl);
    ++m_.ticks;
    m_.makespan = m_.ticks;
    m_.soc = val_->sum_of_costs();
    m_.dependency_waits = drv.stats().dependency_waits;
    m_.chained = drv.stats().chained;
    m_.switches = drv.stats().switches;
    m_.followed = drv.stats().followed;
    m_.overshoot_m = drv.stats().overshoot;
    const planner::Config now = executed();
    if (rules_ && drv.zone_gated()) m_.rules.zone_holds += rules_->count_held(drv.gated(), now);
    count_tick(now);
    if (plan) {  // what the AGVs executed counts; a plan that stood still gets its task step too
      release_completions(adg);
      if (!plan_moved_) plan_update(p_->current(), adg.steps() + static_cast<long long>(oab_->size()));
      plan_moved_ = false;
    }
    if (tm_) {  // this tick's planner time: its steps and the last epoch start; the new one counts next tick
      const double tick_planner_ms = plan_in_tick_ + epoch_ms_;
      epoch_ms_ = 0;
      lifelong_tick(now, tick_planner_ms);
    }
    progress_line(now);
  }
  m_.dependency_waits = drv.stats().dependency_waits;
  m_.chained = drv.stats().chained;
  m_.switches = drv.stats().switches;
  m_.followed = drv.stats().followed;
  m_.overshoot_m = drv.stats().overshoot;
  m_.out_and_backs = oab_->cuts();
  const DriveStats::Time& t = drv.stats().time;
  m_.time_cruise = t.cruise, m_.time_accel = t.accel, m_.time_follow = t.follow;
  m_.time_lane = t.lane, m_.time_end = t.end, m_.time_start_wait = t.start_wait;
  m_.turn_steps = drv.stats().turn_steps;
  m_.split.clear();
  for (int k = 0; k < DriveStats::kSplitCount; ++k) m_.split.emplace_back(DriveStats::split_name(k), drv.stats().split[k]);
  m_.starts_from_rest = drv.stats().starts_from_rest;
  m_.starved_starts = drv.stats().starved_starts, m_.starved_steps = drv.stats().starved_steps;
  if (!drv.trace().empty())
    planner::write_file(dir_ + "/split_trace.txt", [&](std::ostream& out) {
      out << "# per AGV, one letter per SUMO step: 'a' + controller::DriveStats::Split:";
      for (int k = 0; k < DriveStats::kSplitCount; ++k)
        out << ' ' << static_cast<char>('a' + k) << '=' << DriveStats::split_name(k);
      out << '\n';
      for (size_t i = 0; i < drv.trace().size(); ++i) out << cmd_->ids()[i] << ' ' << drv.trace()[i] << '\n';
    });
}

void Run::finish()
{
  if (m_.error.empty() && m_.sim_s == 0) {
    try {
      m_.sim_s = sumo_->time();
    } catch (const SumoError&) {
    }
  }
  m_.loop_s = ms_since(loop0_) / 1000;
  const bool sumo_ran = sumo_->running();  // false: never started, or died (the error says so)
  sumo_->close();                           // flushes SUMO's output files
  // Every output is attempted; the first that failed is reported once all are written.
  std::string write_error;
  auto checked = [&](const std::function<void()>& write) {
    try {
      write();
    } catch (const planner::OutputError& e) {
      if (write_error.empty()) write_error = e.what();
    }
  };
  // A SUMO of several clients (run.order) outlives us: it writes its outputs when it ends.
  if (sumo_ran && cfg_.run.order == 0)
    checked([&] { check_sumo_outputs(cfg_, dir_, cfg_.run.backend == "traci" || cfg_.run.gui ? 10.0 : 0.0); });

  m_.expansions = p_->expansions() + replan_expansions_;
  m_.planner_ms_per_step = Latency::of(plan_step_);
  m_.planner_cpu_ms_per_step = Latency::of(plan_cpu_step_);
  m_.searches_skipped = sb_.searches_skipped;
  m_.planner_ms_per_tick = Latency::of(plan_tick_);
  m_.sumo_ms_per_step = Latency::of(sumo_step_);
  m_.control_ms_per_tick = Latency::of(control_);
  m_.executor_ms_per_step = Latency::of(exec_step_);
  m_.commands = cmd_->stats();
  m_.delay_agent_ticks = delays_->stop_ticks();
  m_.delay_stops = delays_->stops();
  m_.safety_checks = safety_->checks();
  if (rule_check_) m_.rules.checks = rule_check_->checks();
  m_.wall_s = ms_since(wall0_) / 1000;
  if (m_.sim_s == 0) m_.sim_s = m_.ticks * cfg_.run.tick_s;

  // The plan's bound: each AGV alone on its planned path (bound.hpp).
  AloneBound whole = *alone_;
  for (const planner::Config& c : c_.plan_.kept()) whole.add(c);
  std::vector<double> alone = whole.result();
  if (cfg_.run.executor != "lockstep")
    for (double& t : alone) t /= cfg_.run.tick_s;
  for (double t : alone) m_.plan_bound_ticks = tm_ ? m_.plan_bound_ticks + t / alone.size() : std::max(m_.plan_bound_ticks, t);

  const planner::Graph& g = c_.map_.graph;
  if (tm_) {
    m_.epochs = life_.epochs;
    life_.steps = m_.ticks;
    life_.errands_finished = m_.errands_finished;
    life_.tasks_finished = m_.tasks_finished;
    life_.expansions = m_.expansions;
    life_.wall_ms = m_.wall_s * 1000;
    life_.planner_errors = m_.violations;
    if (const tasks::FreeFlowBound* ff = tm_->free_flow()) {
      m_.free_flow_bound = tm_->free_flow_bound();  // finished and open errands (free_flow.hpp)
      m_.free_flow_bound_finished = ff->errands_per_step();
    }
    m_.stalls = tm_->stall_summary();
    if (m_.violations > 0) life_.first_error = m_.error;
    life_.counts = epochs_->counts();
    if (dist_cache_) m_.precompute_pops = static_cast<long long>(dist_cache_->counters().precompute_pops);  // the log's maxErrandTicks, queues and parking, as metrics.json's
    tasks::RunInfo info;
    info.problem = cfg_.path;
    info.solver = p_->name();
    info.mode = cfg_.tasks.assignment;
    info.assigner = cfg_.tasks.assigner;
    info.team_size = m_.agents;
    info.budget_ms = cfg_.planner.budget_ms;
    info.seed = cfg_.tasks.seed;
    nlohmann::json j = tasks::lifelong_log(info, life_);
    tasks::add_task_fields(j, *tm_);
    j["tickS"] = cfg_.run.tick_s;
    j["backend"] = m_.backend;
    j["expansionsPerSumoStep"] = cfg_.planner.expansions;
    j["taskCount"] = static_cast<long long>(cfg_.tasks.random_tasks ? cfg_.tasks.count : cfg_.tasks.list.size());
    j["executor"] = cfg_.run.executor;
    if (!m_.error.empty()) j["error"] = m_.error;
    checked([&] { planner::write_file(dir_ + "/" + cfg_.tasks.log, j.dump(2) + '\n'); });
  }
  if (cfg_.output.congestion && m_.ticks > 0) checked([&] { write_congestion(); });
  if (view_) m_.view = view_->stats();
  if (cfg_.output.plan) {
    planner::PlanHeader h;
    h.map_file = cfg_.sumo.net;
    h.solver = p_->name();
    h.solved = m_.solved;
    h.soc = m_.soc;
    h.soc_lb = m_.soc_lb;
    h.makespan = m_.makespan;
    h.comp_time_ms = m_.planner_ms_per_step.mean * m_.planner_ms_per_step.count;
    h.extra = {{"backend", m_.backend}, {"ticks", std::to_string(m_.ticks)}, {"error", m_.error},
               {"executor", cfg_.run.executor}};
    checked([&] {
      planner::write_file(dir_ + "/plan.txt", [&](std::ostream& out) {
        planner::write_plan_header(out, g, ins_.starts, tm_ ? tm_->goals() : ins_.goals, h);
        c_.plan_.copy_spilled(out);
        planner::write_plan_steps(out, g, c_.plan_.kept(), c_.plan_.first());
      });
    });
  }
  // metrics.json last, so that it says whether an output failed (it said error "" for a run
  // that exited 1 on "cannot write fcd.xml").
  if (m_.error.empty() && !write_error.empty()) m_.error = write_error;
  checked([&] { planner::write_file(dir_ + "/metrics.json", m_.to_json().dump(2) + '\n'); });
  if (!write_error.empty()) throw planner::OutputError(write_error);
}

}  // namespace controller
