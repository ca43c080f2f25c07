#include "run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "controller/fleet.hpp"
#include "controller/instance_bound.hpp"
#include "controller/lane_costs.hpp"
#include "controller/lifelong.hpp"
#include "controller/sumo_error.hpp"
#include "controller/sumo_options.hpp"
#include "gridify/gridifier.hpp"
#include "planner/error.hpp"
#include "planner/output_file.hpp"
#include "planner/plan_io.hpp"
#include "planner/rotation/rotation_planner.hpp"
#include "policy/weights_file.hpp"
#include "tasks/lifelong_goal.hpp"
#include "tasks/lifelong_log.hpp"
#include "tasks/queue_trace.hpp"
#include "tasks/station_queues.hpp"
#include "tasks/stub_mouths.hpp"

namespace controller {

namespace fs = std::filesystem;
using planner::Clock;
using planner::ms_since;

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
    throw FleetError(when + std::string("AGV(s) left the network: ") + join_ids(ids) +
                       " (arrived at a route end or removed behind the controller's back)");
  ids = sumo.teleported();
  if (!ids.empty()) throw FleetError(when + std::string("SUMO teleported AGV(s): ") + join_ids(ids));
  ids = sumo.colliding();
  if (!ids.empty()) throw ControlError(when + std::string("SUMO reports colliding AGV(s): ") + join_ids(ids));
}

}  // namespace

void Run::prepare()
{
  m_.config = cfg_.path;
  m_.net = cfg_.sumo.net;
  m_.solver = cfg_.planner.solver;
  m_.policy = cfg_.planner.policy;
  m_.tick_s = cfg_.run.tick_s;
  m_.step_length = cfg_.sumo.step_length;
  m_.budget_ms = cfg_.planner.budget_ms;
  m_.mode = cfg_.tasks.mode;
  m_.executor = cfg_.run.executor;
  m_.window = cfg_.run.executor != "lockstep" ? cfg_.run.window : 1;
  if (cfg_.tasks.lifelong()) m_.assignment = cfg_.tasks.assignment;

  gridify::GridifyOptions go;
  go.cell_length = cfg_.grid.cell_length;
  go.tolerance = cfg_.grid.tolerance;
  go.snap = cfg_.grid.snap;
  go.drop_one_way = cfg_.grid.drop_one_way;
  go.additional = cfg_.sumo.additional;
  try {
    c_.map_ = gridify::gridify(cfg_.sumo.net, go);
  } catch (const planner::InputError& e) {
    // The message names its file: the additional file's errors are that key's.
    const std::string what = e.what();
    const bool additional = !cfg_.sumo.additional.empty() && what.rfind(cfg_.sumo.additional, 0) == 0;
    throw ConfigError(cfg_.path + (additional ? ": sumo.additional: " : ": sumo.net: ") + what);
  }
  // What gridify left out, one line per kind (rtlacam-gridify lists every item): a run on a
  // net with closed aisles or dropped links says so instead of routing around them silently.
  {
    std::map<std::string, std::pair<int, const gridify::Dropped*>> kinds;
    for (const gridify::Dropped& d : c_.map_.dropped) {
      auto& k = kinds[d.kind];
      if (k.first++ == 0) k.second = &d;
    }
    for (const auto& [kind, k] : kinds)
      std::fprintf(stderr, "[rtlacam-sumo] gridify left out %d %s(s), e.g. %s: %s\n", k.first, kind.c_str(), k.second->id.c_str(),
                   k.second->reason.c_str());
  }
  if (cfg_.run.executor == "lockstep" && cfg_.fleet.vtype.physics_given)
    std::fprintf(stderr,
                 "[rtlacam-sumo] run.executor lockstep drives each AGV a cell per tick at any acceleration: fleet.vtype "
                 "accel / decel / max_speed are not used (adg and adg-follow keep to them)\n");
  // Two AGVs on neighbouring cells of an aisle stand one step apart: SUMO inserts them, and
  // they stand still, only if the step holds a body and its min_gap. config.cpp checks that
  // against grid.cell_length; a snapped aisle's step (a 2.55 m aisle of 1 m cells: 0.85 m)
  // or one fitted within grid.tolerance may be shorter.
  const VType& vt = cfg_.fleet.vtype;
  auto fmt = [](double d) {
    std::ostringstream o;
    o << d;
    return o.str();
  };
  for (const gridify::Aisle& a : c_.map_.aisles)
    if (a.steps > 1 && a.spacing + 1e-9 < vt.length + vt.min_gap)
      throw ConfigError(cfg_.path + ": fleet.vtype: length + min_gap (" + fmt(vt.length + vt.min_gap) +
                        ") exceeds the " + fmt(a.spacing) + " m step of aisle '" + a.ab + "' (" +
                        std::to_string(a.steps) + " steps over " + fmt(a.length_ab) +
                        " m): shorten the AGV or its min_gap, or use a smaller grid.cell_length");
  ins_ = make_instance(cfg_, c_.map_);
  // Random starts and random goals drawn with one seed are the same cells: a run with
  // nothing to do, which looked like an instant success.
  if (!cfg_.tasks.lifelong() && cfg_.fleet.random_starts && cfg_.tasks.random_goals && ins_.goals == ins_.starts)
    std::fprintf(stderr, "[rtlacam-sumo] every random goal is its AGV's start (tasks.seed %llu draws the cells fleet.seed %llu "
                         "does): give tasks.seed another value\n",
                 static_cast<unsigned long long>(cfg_.tasks.seed), static_cast<unsigned long long>(cfg_.fleet.seed));
  const planner::Graph& g = c_.map_.graph;
  // Random starts (and one-shot random goals) that a one-at-a-time zone would refuse: each
  // zone keeps one, the rest move to the nearest free cell outside (fleet.hpp).
  if (cfg_.fleet.random_starts || (!cfg_.tasks.lifelong() && cfg_.tasks.random_goals)) {
    std::vector<std::vector<planner::Vertex>> zones;
    for (Zone& z : Rules::zones_of(cfg_, c_.map_)) zones.push_back(std::move(z.cells));
    int starts = 0, goals = 0;
    if (!zones.empty() && cfg_.fleet.random_starts) starts = keep_out_of_zones(g, zones, ins_.starts);
    if (cfg_.tasks.lifelong()) ins_.goals = ins_.starts;
    else if (!zones.empty() && cfg_.tasks.random_goals) goals = keep_out_of_zones(g, zones, ins_.goals);
    if (starts + goals > 0)
      std::fprintf(stderr, "[rtlacam-sumo] %d random start(s) and %d random goal(s) moved out of one-at-a-time zones (one AGV per zone)\n",
                   starts, goals);
  }
  m_.agents = ins_.num_agents();
  m_.cells = g.size();
  if (!cfg_.tasks.lifelong()) m_.soc_lb = ins_.soc_lower_bound(g);  // in moves: before the lane costs
  if (cfg_.planner.lane_costs) {
    // Slow lanes cost more in every distance table on this graph (lane_costs.hpp): the
    // planner's heuristics and the task assigners' distances. The AGVs' top speed: a cell
    // per tick in lockstep, the vType's otherwise.
    double spacing = 0;
    for (const gridify::Aisle& a : c_.map_.aisles) spacing = std::max(spacing, a.spacing);
    const double top = cfg_.run.executor == "lockstep" ? spacing / cfg_.run.tick_s : cfg_.fleet.vtype.max_speed;
    if (top > 0) c_.map_.graph.set_move_costs(lane_costs(c_.map_, top));
    m_.costly_cells = 0;
    for (uint8_t k : c_.map_.graph.move_costs()) m_.costly_cells += k > 1;
  }
  std::unique_ptr<tasks::FreeFlowBound> free_flow;  // lifelong: given to the task layer at its start
  if (cfg_.tasks.lifelong()) {
    const std::shared_ptr<const tasks::TaskFile> file = make_task_file(cfg_, c_.map_);
    const std::vector<planner::Vertex> stations = file->errand_cells();
    if (const tasks::QueueOptions q = task_layer_options(cfg_, c_.map_).queues; q.on() && q.one_way) {
      // One-way queue lanes (tasks/station_queues.hpp): the graph every planner, table and
      // check of this run uses; SUMO's lanes stay as they are. Before the mouth costs, so the
      // driven graph below is a copy of it (neither rule reads the other: the lanes ignore move
      // costs, the mouths look along arcs both ways).
      // A station named as the user knows it: its SUMO stop, else the cell's place on the net.
      auto name = [&](planner::Vertex v) {
        const gridify::Cell& cell = c_.map_.cells[v];
        if (!cell.stations.empty()) return "'" + c_.map_.stations[cell.stations[0]].id + "'";
        char xy[64];
        std::snprintf(xy, sizeof xy, "(%.1f, %.1f)", cell.x, cell.y);
        return std::string("the cell at ") + xy;
      };
      try {
        c_.map_.graph = tasks::one_way_queue_lanes(c_.map_.graph, stations, q, name);
      } catch (const std::invalid_argument& e) {
        throw ConfigError(cfg_.path + ": tasks.queues.one_way: " + e.what());
      }
    }
    if (cfg_.tasks.urgency_mouth_cost > 0) {
      // Routing past stations costs more (tasks/stub_mouths.hpp): every distance table on
      // this graph (planner, assigners) sees it; the free-flow bound keeps the driven graph.
      drive_graph_ = std::make_unique<planner::Graph>(c_.map_.graph);
      c_.map_.graph.set_move_costs(tasks::mouth_costs(c_.map_.graph, stations, cfg_.tasks.urgency_mouth_cost));
    }
    tm_ = make_task_manager(cfg_, c_.map_, file);
    // The free-flow bound (tasks/free_flow.hpp) prices an errand's shortest path as the
    // executor would drive it alone: a cell per tick in lockstep, one rest-to-rest trapezoid
    // of the vType otherwise (bound.hpp). Its own cache: the planner's has a step deadline.
    tasks::FreeFlowBound::Cost cost;
    if (cfg_.run.executor != "lockstep")
      cost = [kin = kinematics(), cell = cfg_.grid.cell_length, tick = cfg_.run.tick_s](int moves) {
        return rest_to_rest_s(moves * cell, kin) / tick;
      };
    free_flow = std::make_unique<tasks::FreeFlowBound>(std::make_shared<planner::DistCache>(drive_graph_ ? *drive_graph_ : c_.map_.graph, 256), cost);
    epochs_ = std::make_unique<tasks::LifelongEpochs>(*tm_, life_);
  }
  if (const tasks::Battery* b = tm_ ? tm_->battery() : nullptr) {
    for (size_t i = 0; i < b->chargers().size(); ++i)
      if (!b->dead_end(static_cast<int>(i)))
        std::fprintf(stderr,
                     "[rtlacam-sumo] warning: fleet.battery: chargingStation '%s' is not at a dead end: traffic can push a "
                     "charging AGV off it (charging pauses meanwhile)\n",
                     b->chargers()[i].id.c_str());
    // Supply against drain: with every AGV driving (a move and a turn per tick, as fast as the
    // executor lets it), the fleet must not drive away more than half of what the chargers give,
    // or AGVs run empty once traffic flows (s42: 200 AGVs at 0.1 Wh/m on 16 chargers, 192 of
    // them empty in 2000 ticks; at 0.025 Wh/m none).
    const tasks::BatteryOptions& o = b->options();
    if (o.charging) {
      double supply = 0;
      for (const tasks::Charger& c : b->chargers()) supply += c.wh_per_step;
      const double moves = cfg_.run.executor == "lockstep"
                               ? 1.0
                               : std::max(1.0, cfg_.fleet.vtype.max_speed * cfg_.run.tick_s / cfg_.grid.cell_length);
      const double drain = ins_.num_agents() * moves * (o.per_m_wh * cfg_.grid.cell_length + o.per_turn_wh);
      if (drain > supply / 2)
        std::fprintf(stderr,
                     "[rtlacam-sumo] warning: fleet.battery: %d AGVs driving drain up to %.1f Wh per tick, the %zu "
                     "chargers give %.1f: AGVs may run empty (size the chargers for at least twice the drain)\n",
                     ins_.num_agents(), drain, b->chargers().size(), supply);
    }
  }
  // The learned policy (CS-PIBT move order). Its observations are grid windows: the net
  // must be an axis-aligned lattice (gridify then attaches the grid view). The planner
  // tells it the goals (ActionPreference::set_goals), so it starts with none.
  if (!cfg_.planner.policy.empty()) {
    if (!g.is_grid())
      throw ConfigError(cfg_.path + ": planner.policy: needs a net whose cells lie on a lattice ('" + cfg_.sumo.net +
                        "' does not: its observations are grid windows)");
    try {
      model_ = policy::load_weights(cfg_.planner.policy);
    } catch (const planner::InputError& e) {
      throw ConfigError(cfg_.path + ": planner.policy: " + e.what());
    }
    pref_ = std::make_unique<policy::PolicyPreference>(g, model_, planner::Config{});
  }
  dir_ = cfg_.output.dir;
  // The vType file written there goes to SUMO's -a, a list SUMO splits at commas.
  if (dir_.find(',') != std::string::npos)
    throw ConfigError(cfg_.path + ": output.dir: '" + dir_ + "' contains ',' (SUMO splits its file lists at commas)");
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (!fs::is_directory(dir_))
    throw ConfigError(cfg_.path + ": output.dir: cannot create '" + dir_ + "'" +
                      (ec ? ": " + ec.message() : fs::exists(dir_) ? ": a file of that name is there" : ""));
  for (const gridify::Aisle& a : c_.map_.aisles) max_spacing_ = std::max(max_spacing_, a.spacing);

  sumo_ = make_backend(cfg_.run);
  m_.backend = sumo_->name();
  cmd_ = std::make_unique<Commander>(c_.map_, *sumo_, cfg_.run.tick_s);
  if (const std::string why = cmd_->net_problem(); !why.empty())
    throw ConfigError(cfg_.path + ": sumo.net: " + cfg_.sumo.net + ": " + why);
  safety_ = std::make_unique<Safety>(c_.map_, cfg_.fleet.vtype.length);
  safety_->set_following(cfg_.run.executor == "adg-follow");
  planner::Config goals = ins_.goals;
  planner::GoalTest goal_test;
  auto setup0 = Clock::now();
  if (tm_) {
    // Duplicate goals are normal here (two AGVs sent to one station): the lifelong goal
    // test ("some AGV not yet arrived stands on its goal") never needs distinct goals.
    // Errand times and stalls (tasks/errand_stalls.hpp) on the net's graph (lane costs
    // included, not tasks.urgency.mouth_cost's routing costs), closures or not: tables of
    // their own, exact whatever the step's deadline.
    epochs_->start(drive_graph_ ? *drive_graph_ : g, ins_.starts, std::move(free_flow));
    if (cfg_.output.queue_trace > 0 && tm_->queues()) {
      try {
        queue_trace_ = std::make_unique<tasks::QueueTrace>((fs::path(dir_) / "queue_trace.txt").string(), cfg_.output.queue_trace, g);
      } catch (const std::runtime_error& e) {
        throw ConfigError(cfg_.path + ": output.queue_trace: " + e.what());
      }
    }
    goals = tm_->goals();
    goal_test = tasks::lifelong_goal_test(*tm_, ins_.starts);
  }
  // Rotation solvers: AGVs with a heading, the lattice's (planner/heading.hpp), each facing
  // along its start lane.
  // A cell solver with fleet.turn_s (adg): the same headings, which only the Driver uses.
  std::vector<int> headings;
  if (cfg_.fleet.headings(cfg_.planner.rotation_solver())) {
    if (!g.is_grid())
      throw ConfigError(cfg_.path + ": " +
                        (cfg_.planner.rotation_solver() ? "planner.solver: " + cfg_.planner.solver
                                                        : std::string("fleet.turn_s: turning on the cells")) +
                        " needs a net whose cells lie on an axis-aligned lattice ('" + cfg_.sumo.net + "' does not)");
    headings = cmd_->start_headings(ins_.starts);
    cmd_->use_headings(headings, static_cast<int>(std::lround(cfg_.fleet.turn_s / cfg_.sumo.step_length)));
    start_headings_ = headings;
    if (!cfg_.planner.rotation_solver()) headings.clear();  // the planner plans cells
  }
  if (!cfg_.planner.rotation_solver()) dist_cache_ = std::make_shared<planner::DistCache>(g);
  try {
    p_ = make_planner(cfg_.planner, g, ins_.starts, goals, pref_.get(), goal_test, headings, dist_cache_);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(cfg_.path + ": planner: " + e.what());
  }
  cap_dist_tables();
  if (tm_) life_.setup_ms = ms_since(setup0);
  val_ = std::make_unique<planner::Validator>(g, ins_.starts, goals);
  delays_ = std::make_unique<executor::DelayModel>(cfg_.delays.spec, ins_.num_agents());
  if (cfg_.run.executor != "lockstep" && cfg_.run.replan_on_stuck && !cfg_.planner.rotation_solver())
    stuck_ = std::make_unique<StuckWatch>(ins_.num_agents(), cfg_.run.stuck_after_s, cfg_.sumo.step_length, cfg_.run.stuck_learn);
  budget_ = planner::Budget{cfg_.planner.budget_ms > 0 ? cfg_.planner.budget_ms : planner::Budget{}.ms,
                            cfg_.planner.expansions > 0 ? cfg_.planner.expansions : planner::Budget{}.expansions};
  // With a time budget the search starts an expansion only if its costliest one so far
  // still ends by the deadline (an expansion cannot stop halfway): p99 near the budget.
  if (cfg_.planner.budget_ms > 0) budget_.reserve_ms = 1e-3;
  // The SUMO step's budget, as the grid's (tasks/step_budget.hpp): planner.budget_ms bounds
  // the planner thread's CPU; the reserve is the dearest expansion of the last 16 searches
  // (detours after a stuck replan stay dear for ~10 steps), and table growth keeps a quarter
  // of what is left at least (a search on lower bounds alone would stall); never two
  // searches skipped in a row.
  const tasks::LifelongOptions grid;
  sb_ = tasks::StepBudget(budget_, grid.expansion_deviations, grid.precompute_share, dist_cache_ != nullptr);
  sb_.cpu_clock = true;
  sb_.reserve_cap = 0.75;
  sb_.reserve_window = 16;
  sb_.max_skips = 1;
  k_ = cfg_.steps_per_tick();
  if (cfg_.output.congestion) congestion_ = std::make_unique<Congestion>(g.size());
  // Traffic rules (rules.hpp): bad input is a ConfigError here, before SUMO starts.
  std::vector<std::string> warnings;
  rules_ = Rules::make(cfg_, c_.map_, ins_.starts, tm_ ? planner::Config{} : ins_.goals, warnings);
  for (const std::string& w : warnings) std::fprintf(stderr, "[rtlacam-sumo] warning: %s\n", w.c_str());
  if (rules_) {
    rule_check_ = std::make_unique<RuleCheck>(c_.map_, *rules_);
    m_.rules.active = true;
    rules_->update(0, nullptr);
    // The zones as a rule of the cell solvers' steps (rules.plan_zones; rotation solvers: admission only).
    if (cfg_.rules.enforce_zones && cfg_.rules.zones_in_planner(cfg_.run.executor) && !rules_->zones().empty() &&
        !cfg_.planner.rotation_solver()) {
      std::vector<std::vector<planner::Vertex>> cells;
      for (const Zone& z : rules_->zones()) cells.push_back(z.cells);
      plan_zones_ = planner::Zones::from_cells(g.size(), cells);
    }
    m_.rules.max_closed = rules_->num_closed();
    closure_tasks();
    // Only watched lanes: the planner stays the one built above until one closes.
    if (rules_->configured()) rules_restart(ins_.starts);
  }
  // Preprocessing (as the grid's, before the first step): the next goals' tables; the first
  // ones grew when the planner was built.
  prefetch_ = tm_ && cfg_.planner.prefetch;
  if (prefetch_) {
    const auto t0 = Clock::now();
    prefetch_goals(true);
    life_.setup_ms += ms_since(t0);
  }
  // adg: the replans (stuck AGVs, rules) re-validate the cut plan from the final prefix.
  if (stuck_ || (rules_ && cfg_.run.executor != "lockstep")) val_final_.emplace(g, ins_.starts, goals);
}

void Run::rules_restart(const planner::Config& at)
{
  const double c0 = planner::thread_cpu_ms();
  zone_occ_ = cfg_.rules.enforce_zones ? rules_->blocked_zones(at) : std::vector<uint8_t>(rules_->zones().size(), 0);
  std::vector<std::string> lanes;  // each AGV's SUMO lane (none before the first step)
  for (const VehiclePose& p : last_poses_) lanes.push_back(p.lane);
  auto g = std::make_unique<planner::Graph>(
      rules_->graph(zone_occ_, cfg_.rules.enforce_closures, rules_->frozen_cells(at, lanes)));
  const planner::Config eff = rule_goals(*g, at);
  planner::GoalTest test;
  if (tm_) test = tasks::lifelong_goal_test(*tm_, at);
  if (p_) replan_expansions_ += p_->expansions();
  // Rotation solvers: the headings its executed actions left each AGV with. The old
  // planner's are those at its current configuration, which is `at` or differs from it only
  // by forward moves admit() held (a held F keeps its heading).
  std::vector<int> headings;
  if (p_ && p_->rotation()) headings = p_->rotation()->headings();
  // The old planner goes first (it still refers to the old graph), then the old graph.
  p_ = make_planner(cfg_.planner, *g, at, eff, pref_.get(), test, headings, nullptr, plan_zones_);
  rules_graph_ = std::move(g);
  cap_dist_tables();
  p_->search(plan_budget());
  sb_.charge(0, planner::thread_cpu_ms() - c0);
  ++m_.rules.replans;
}

void Run::closure_tasks()
{
  if (!tm_ || !cfg_.rules.enforce_closures || !cfg_.rules.reassign) return;
  // Zones are left open here: an occupied zone empties soon, a closure lasts.
  std::unique_ptr<planner::Graph> g;
  if (rules_->anything_closed())  // cells, or arcs closed one way
    g = std::make_unique<planner::Graph>(rules_->graph(std::vector<uint8_t>(rules_->zones().size(), 0), true));
  tm_->set_open_graph(g.get());  // the next tm_->update() hands back what they cut off
  open_graph_ = std::move(g);
}

planner::Config Run::rule_goals(const planner::Graph& g, const planner::Config& at)
{
  std::vector<std::string> lines;
  const planner::Config eff = rules_->goals(g, at, goals(), waiting_, m_.ticks * cfg_.run.tick_s, lines);
  for (const std::string& l : lines) std::fprintf(stderr, "[rtlacam-sumo] %s\n", l.c_str());
  return eff;
}

bool Run::rules_update()
{
  const double t = m_.ticks * cfg_.run.tick_s;
  const auto t0 = Clock::now();
  const bool changed = rules_->update(t, sumo_.get());
  m_.rules.poll_ms += ms_since(t0);
  if (changed) {
    std::vector<std::string> edges;  // SUMO refuses routes through these now
    for (const std::string& l : rules_->lanes_closed()) edges.push_back(l.substr(0, l.rfind('_')));
    cmd_->avoid_edges(std::move(edges));
    ++m_.rules.closure_changes;
    m_.rules.max_closed = std::max(m_.rules.max_closed, rules_->num_closed());
    std::fprintf(stderr, "[rtlacam-sumo] t=%.1f s: %d cell(s) closed, %zu arc(s) closed one way\n", t,
                 rules_->num_closed(), rules_->closed_arcs().size());
    closure_tasks();
  }
  return changed;
}

void Run::rules_tick(const planner::Config& cur)
{
  if (rules_update()) {
    rules_restart(cur);
  } else if (cfg_.rules.enforce_zones && rules_->blocked_zones(cur) != zone_occ_) {
    rules_restart(cur);
  }
  for (uint8_t w : waiting_) m_.rules.waits += w;
}

void Run::rules_tick_adg(executor::Adg& adg, Driver& drv)
{
  const bool changed = rules_update();
  planner::Config at(ins_.num_agents());
  for (int i = 0; i < ins_.num_agents(); ++i) at[i] = adg.at(i);
  // (enforce_closures off: the planner keeps its graph, RuleCheck sees what follows.)
  const bool regraph = (changed && cfg_.rules.enforce_closures) ||
                       (cfg_.rules.enforce_zones && rules_->blocked_zones(at) != zone_occ_);
  if (regraph) {
    const std::vector<uint8_t> none(ins_.num_agents(), 0);
    replan(adg, drv, stuck_ ? stuck_->immobile() : none, true);
  }
  for (uint8_t w : waiting_) m_.rules.waits += w;
}

planner::Budget Run::startup_budget() const
{
  planner::Budget b = plan_budget();
  // A tick's budget (a rotation solver's plan_budget() is one already), startup_ticks times;
  // 0: the insertion step's own.
  const int ticks = cfg_.planner.startup_ticks;
  if (ticks == 0) return b;
  const double f = static_cast<double>(ticks) * (p_->rotation() ? 1 : k_);
  b.ms *= f;  // infinity stays infinity
  if (b.expansions != planner::Budget{}.expansions) b.expansions = static_cast<uint64_t>(static_cast<double>(b.expansions) * f);
  return b;
}

planner::Budget Run::plan_budget() const
{
  planner::Budget b = budget_;
  if (p_->rotation() && cfg_.planner.budget_ms > 0) b.ms *= k_;  // Run::step(): a tick's budget
  return b;
}

std::vector<VehiclePose> Run::poses()
{
  try {
    return sumo_->poses(cmd_->ids());
  } catch (const SumoError& e) {
    if (!sumo_->running()) throw;
    cmd_->verify(p_->current(), 1e9);  // names an AGV that is gone, if one is
    throw;
  }
}

void Run::step(const std::vector<std::vector<planner::Vertex>>& allowed, bool exclusive, const std::vector<int>& groups)
{
  auto t0 = Clock::now();
  const double c0 = planner::thread_cpu_ms();
  // The step's budget covers its commits (and an epoch start or replan) too: the carry
  // (StepBudget) charged since the last step's search.
  planner::Budget b = budget_;
  planner::RotationPlanner* rot = p_->rotation();
  // A rotation solver plans a tick's step in one search() call and cannot spread it over
  // the tick's SUMO steps: that call (the tick's first slice) gets the tick's budget, and
  // the other slices grow its distance tables (measured: epibt with 1 ms for 200 AGVs timed
  // out every step, 0.055 errands/tick on the large warehouse).
  if (rot && slice_ == 0) b = plan_budget();
  const double full_ms = b.ms;
  b = sb_.left(b);
  if (rot && slice_ > 0 && cfg_.planner.budget_ms > 0) {
    rot->precompute(b.deadline_from(t0));
  } else {
    // The distance tables stop growing at the step's deadline too (lower bounds past it,
    // grown by a later step: dist_cache.hpp), and so do the detours around stuck AGVs
    // (immobile.hpp): after a stuck replan one search expansion of 1000 agents would
    // otherwise search every goal's detour at once (10 ms and more).
    // They stop one expansion's own work before it (StepBudget::tables_ms): the expansion
    // that meets the deadline still has that to do (measured on huge_warehouse_agv, 1000
    // AGVs, 1 ms: 1.3-2.0 ms per step in the ~10 steps after each stuck replan without it).
    const bool bounded = sb_.bounded;
    // The carry may have used the step's budget already: then no search at all, where the
    // search would still run its one forced expansion (StepBudget::skip; never two steps in
    // a row, so the search always progresses).
    if (!sb_.skip(cfg_.planner.budget_ms > 0, full_ms, b.ms)) {
      const auto end = b.deadline_from(t0);  // the step's: the search gets what the prefetched tables leave
      planner::Budget tb = b;
      tb.ms = sb_.tables_ms(b.ms);
      if (bounded && cell_prefetch()) b.ms = std::max(0.0, b.ms - precompute_first(b, t0));
      if (bounded) dist_cache_->set_deadline(tb.deadline_from(t0));
      const double s0 = planner::thread_cpu_ms();
      const uint64_t e0 = p_->expansions();
      p_->search(b);
      sb_.expanded(planner::thread_cpu_ms() - s0, p_->expansions() - e0);
      if (bounded) dist_cache_->set_deadline(planner::DistCache::Deadline::max());
      // The search ended early: the rest of the step grows the tables to come. How far that
      // ran past the deadline, when the deadline stopped it, is the guard's sample (a sample
      // above a tenth of the budget is preemption, not work), as the grid's.
      if (bounded && cell_prefetch() && dist_cache_->pending() > 0 && Clock::now() < end) {
        dist_cache_->precompute(end);
        if (dist_cache_->pending() > 0) sb_.overrun.add(std::clamp(ms_since(end), 0.0, 0.1 * budget_.ms));
      }
    }
  }
  plan_cpu_step_.push_back(planner::thread_cpu_ms() - c0 + sb_.carry_cpu_ms);
  sb_.paid();
  const double ms = ms_since(t0);
  plan_step_.push_back(ms);
  plan_in_tick_ += ms;
  if (c_.on_step) c_.on_step(*sumo_, last_poses_);
  sumo_->request_poses();
  t0 = Clock::now();
  sumo_->step();
  sumo_step_.push_back(ms_since(t0));
  check_events(*sumo_, sumo_->time());
  t0 = Clock::now();
  last_poses_ = poses();
  for (size_t i = 0; i < last_poses_.size(); ++i)
    if (last_poses_[i].lane.empty())
      throw FleetError("AGV " + cmd_->ids()[i] + " (agent " + std::to_string(i) +
                       ") is not in SUMO any more (removed behind the controller's back?)");
  safety_->check(last_poses_, allowed, cmd_->ids(), sumo_->time(), exclusive, groups);
  if (rule_check_) rule_check_->check(last_poses_, cmd_->ids(), sumo_->time());
  exec_step_.push_back(ms_since(t0));
}

void Run::prefetch_goals(bool now)
{
  if (cell_prefetch()) {
    epochs_->prefetch(*dist_cache_, p_->current());
    if (now) dist_cache_->precompute(Clock::time_point::max());
  } else if (planner::RotationPlanner* rot = prefetch_ ? p_->rotation() : nullptr) {
    epochs_->prefetch(*rot);
    if (now) rot->precompute(Clock::time_point::max());
  }
}

double Run::precompute_first(const planner::Budget& b, planner::Clock::time_point t0)
{
  if (dist_cache_->pending() == 0) return 0;
  // Tables first: an expansion that meets an incomplete table would pay its BFS anyway, all
  // at once. It leaves room for the one expansion the search always makes (StepBudget).
  const double share = sb_.precompute_ms(b.ms);
  if (share <= 0) return 0;
  const auto t1 = Clock::now();
  dist_cache_->precompute(planner::Budget::time_ms(share).deadline_from(t0));
  return ms_since(t1);
}

void Run::start_sumo()
{
  if (cfg_.run.gui) write_gui_settings(cfg_, dir_);  // sumo_args names it
  sumo_->start(sumo_args(cfg_, dir_, write_vtype_file(cfg_, dir_, max_spacing_), cmd_->needs_ignore_route_errors()));
  cmd_->insert(ins_.starts);
  // Insertion step (the AGVs are pending until it): no safety check before they exist.
  // The first command waits for a tick's planning (planner.startup_ticks), as every later one
  // does; before the clock starts, so no SUMO step holds it (metrics.json planner_startup).
  {
    const auto t0 = Clock::now();
    const double c0 = planner::thread_cpu_ms();
    p_->search(startup_budget());
    m_.planner_startup_ms = ms_since(t0);
    m_.planner_startup_cpu_ms = planner::thread_cpu_ms() - c0;
    m_.planner_startup_expansions = p_->expansions();
  }
  sumo_->step();
  check_events(*sumo_, sumo_->time());
  const std::vector<std::string> waiting = sumo_->pending();
  if (!waiting.empty()) throw FleetError("SUMO could not insert AGV(s) on their start cells: " + join_ids(waiting));
  cmd_->verify(ins_.starts, c_.tolerance);
  // Every AGV idle (grey) and its goal marked before the first tick; changes only after.
  view_ = std::make_unique<FleetView>(*sumo_, c_.map_, cmd_->ids(), 0.7 * cfg_.grid.cell_length);
  view_->show(std::vector<AgvState>(ins_.num_agents(), AgvState::Idle));
  show_goals();
}

void Run::lifelong_tick(const planner::Config& executed, double tick_planner_ms)
{
  life_.planner_ms.push_back(tick_planner_ms);
  if (!epoch_early() && !plan_mode()) epoch_start(executed, m_.ticks);  // plan mode: loop_adg
  epochs_->count(m_.ticks, executed);  // goal ticks, queue and parking counts (tasks/lifelong_epochs.hpp)
  const tasks::EpochCounts& n = epochs_->counts();
  m_.max_errand_ticks = n.max_goal_ticks;
  m_.max_heading = n.max_heading;
  m_.queued_ticks = n.queued_ticks;
  m_.clearings = n.clearings;
  m_.jam_clearings = n.jam_clearings;
  m_.clearing_steps = n.clearing_steps;
  m_.longest_clearing = n.longest_clearing;
  m_.idle_at_end = n.idle;
  m_.parked_at_end = n.parked;
  m_.idle_ticks = n.idle_ticks, m_.parked_ticks = n.parked_ticks;
  m_.errands_finished = plan_mode() ? plan_errands_ : tm_->errands_finished();
  m_.tasks_finished = plan_mode() ? plan_tasks_ : tm_->tasks_finished();
  m_.reassigned_for_closure = tm_->reassigned_for_closure();
  if (const tasks::Battery* b = tm_->battery()) count_battery(*b), m_.battery.dropped_mid_task = tm_->dropped_for_charge();
}

bool Run::epoch_early() const
{
  // Lockstep knows a tick's outcome when it commands it: the epoch start moves to the tick's
  // start, and its new tree is searched in the tick's own SUMO steps. Not with rules (their
  // goals depend on the time) nor with a rotation solver (it plans a tick in one call).
  return cfg_.run.epoch_in_budget && cfg_.run.executor == "lockstep" && !rules_ && !p_->rotation();
}

void Run::epoch_start(const planner::Config& executed, long tick)
{
  // The task layer at the end of tick `tick` (1-based, where the AGVs are then). Completed
  // errands start a new epoch: new goals, a fresh tree rooted at the planner's current
  // configuration, and a search slice for the tree's first move. It is the next SUMO step's
  // planning (StepBudget's carry), so with a time budget it is bounded by that step's: the
  // distance queries of set_goals stop growing tables at the step's deadline (lower bounds
  // past it; later steps grow them), and the search gets only what is left (a resumable
  // expansion pauses at its deadline; the next steps go on with it).
  auto t0 = Clock::now();
  const bool changed = epochs_->complete(tick, executed);
  if (queue_trace_) queue_trace_->step(tick, *tm_, executed, epochs_->completed());
  if (!changed) return;
  const double c0 = planner::thread_cpu_ms();
  // Rules: goals a closure cuts off wait (rules.hpp).
  const bool bounded = epoch_goals(rules_graph_ ? rule_goals(*rules_graph_, p_->current()) : tm_->goals(), t0);
  if (!epochs_->completed().empty()) prefetch_goals(false);  // queued: later steps grow them
  val_->set_goals(tm_->goals());
  planner::Budget b = plan_budget();
  if (bounded) b.ms = std::max(0.0, sb_.left(b).ms - (planner::thread_cpu_ms() - c0));
  if (!bounded || b.ms > 0) p_->search(b);
  if (bounded) dist_cache_->set_deadline(planner::DistCache::Deadline::max());
  sb_.charge(0, planner::thread_cpu_ms() - c0);
  show_goals();  // the view's work, not the planner's
  epochs_->record(true);
  epoch_ms_ += ms_since(t0);
}

bool Run::epoch_goals(const planner::Config& goals, Clock::time_point t0)
{
  const bool bounded = dist_cache_ && cfg_.planner.budget_ms > 0 && !p_->rotation() && cfg_.run.epoch_in_budget;
  // Its tables stop one expansion's reserve before the step's end, the reserve capped at a
  // share of the whole step (not of what the carry left: the epoch start is not the search).
  if (bounded)
    dist_cache_->set_deadline(
        planner::Budget::time_ms(std::max(0.0, sb_.left(budget_).ms - sb_.reserve(budget_.ms))).deadline_from(t0));
  const uint64_t est0 = dist_cache_ ? dist_cache_->counters().estimates : 0;
  epochs_->start_epoch(*p_, goals);
  if (dist_cache_) m_.epoch_estimates += static_cast<long long>(dist_cache_->counters().estimates - est0);
  return bounded;
}

bool Run::plan_mode() const
{
  return tm_ && cfg_.run.plan_completions && cfg_.run.executor != "lockstep" && !rules_ && !tm_->battery() && !p_->rotation();
}

planner::Config Run::plan_goals() const
{
  planner::Config g = tm_->goals();
  for (size_t a = 0; a < debts_.size(); ++a)
    if (!debts_[a].empty()) g[a] = debts_[a].front().cell;
  return g;
}

void Run::plan_update(const planner::Config& c, long long step)
{
  const auto t0 = Clock::now();
  const double c0 = planner::thread_cpu_ms();
  plan_moved_ = true;
  // Debts first (a replan cut their visit): a commit on the debt's cell pays it.
  bool paid = false;
  planner::Config seen = c;
  for (size_t a = 0; a < debts_.size(); ++a) {
    if (debts_[a].empty()) continue;
    if (c[a] == debts_[a].front().cell) {
      PlanCompletion d = debts_[a].front();
      debts_[a].erase(debts_[a].begin());
      d.step = step;
      pending_.push_back(d);
      paid = true;
    }
    if (!debts_[a].empty()) seen[a] = debts_[a].front().cell;  // its later errands wait for the visit
  }
  const bool changed = epochs_->complete(++task_clock_, seen) || paid;
  if (queue_trace_) queue_trace_->step(task_clock_, *tm_, seen, epochs_->completed());
  const tasks::TaskFile& f = tm_->file();
  for (const tasks::Event& e : epochs_->completed()) {
    const auto& errands = f.tasks[static_cast<size_t>(e.task % static_cast<long>(f.size()))];
    pending_.push_back({e, step, e.errand + 1 >= static_cast<int>(errands.size()), c[e.agent]});
    ++m_.plan_completions;
  }
  if (changed) {
    // No search slice here: the next SUMO step's search starts on the new tree. Its
    // set_goals reads distances within this step's budget, as epoch_start's.
    const planner::Config goals = plan_goals();
    if (epoch_goals(goals, t0)) dist_cache_->set_deadline(planner::DistCache::Deadline::max());
    if (!epochs_->completed().empty()) prefetch_goals(false);
    val_->set_goals(goals);
    show_goals();
  }
  epochs_->record_epoch(changed);  // the events are recorded when executed
  sb_.charge(0, planner::thread_cpu_ms() - c0);
  epoch_ms_ += ms_since(t0);
}

void Run::release_completions(const executor::Adg& adg)
{
  std::vector<tasks::Event> done;
  size_t w = 0;
  for (PlanCompletion& q : pending_) {
    if (adg.progress(q.ev.agent) >= q.step) {
      q.ev.t = m_.ticks;
      done.push_back(q.ev);
      ++plan_errands_;
      plan_tasks_ += q.task_done;
    } else {
      pending_[w++] = q;
    }
  }
  pending_.resize(w);
  epochs_->record_events(done);
}

void Run::plan_debts(const std::vector<long long>& prog, const std::vector<planner::Config>& steps)
{
  // prog: each AGV's progress in the ADG being replaced; steps: the new ADG's first
  // configurations after its start (the moves in progress).
  if (debts_.empty()) debts_.resize(ins_.num_agents());
  size_t w = 0;
  for (PlanCompletion& q : pending_) {
    const int a = q.ev.agent;
    if (prog[a] >= q.step) {  // executed already: counted at this tick's end
      q.step = 0;
      pending_[w++] = q;
      continue;
    }
    long long at = -1;  // the target of a move in progress: the new ADG executes it
    for (size_t t = 0; t < steps.size() && at < 0; ++t)
      if (steps[t][a] == q.cell) at = static_cast<long long>(t) + 1;
    if (at >= 0) {
      q.step = at;
      pending_[w++] = q;
    } else {
      debts_[a].push_back(q);
      ++m_.plan_debts;
    }
  }
  pending_.resize(w);
}

void Run::count_battery(const tasks::Battery& b)
{
  Metrics::BatteryStats& s = m_.battery;
  const double cap = b.options().capacity_wh;
  if (!s.active) {
    s.active = true;
    s.capacity_wh = cap;
    s.charging = b.options().charging;
  }
  const std::vector<double>& q = b.charges();
  for (int a : b.emptied())
    std::fprintf(stderr, "[rtlacam-sumo] warning: t=%.1f s: %s ran empty (fleet.battery: charge 0 of %g Wh)\n",
                   m_.ticks * cfg_.run.tick_s, cmd_->ids()[a].c_str(), cap);
  for (double c : q) s.min_charge = std::min(s.min_charge, c / cap);
  s.ran_empty = b.ran_empty();
  s.errands = b.errands();
  s.charging_share = b.agent_ticks() > 0 ? static_cast<double>(b.charging_ticks()) / b.agent_ticks() : 0.0;
  if (m_.ticks % cfg_.fleet.battery.sample_ticks == 0 && !q.empty()) {
    double lo = q[0], hi = q[0], sum = 0;
    for (double c : q) lo = std::min(lo, c), hi = std::max(hi, c), sum += c;
    s.samples.push_back({m_.ticks, lo / cap, sum / q.size() / cap, hi / cap});
  }
}

void Run::progress_line(const planner::Config& executed)
{
  if (cfg_.run.progress_s <= 0 || std::chrono::duration<double>(Clock::now() - last_progress_).count() < cfg_.run.progress_s)
    return;
  last_progress_ = Clock::now();
  const double wall = ms_since(wall0_) / 1000;
  if (tm_) {
    std::fprintf(stderr,
                 "[rtlacam-sumo] tick %lld/%lld  errands %lld (%.3f/tick)  tasks %lld (%.3f/tick)  planner p99 %.2f "
                 "ms/tick  wall %.1f s (%.0fx real time)\n",
                 m_.ticks, cfg_.run.max_ticks, m_.errands_finished, m_.errand_throughput(), m_.tasks_finished,
                 m_.throughput(), tasks::summarize(life_.planner_ms).p99, wall,
                 wall > 0 ? m_.ticks * cfg_.run.tick_s / wall : 0.0);
  } else {
    int at_goal = 0;
    for (int i = 0; i < ins_.num_agents(); ++i) at_goal += executed[i] == ins_.goals[i];
    std::fprintf(stderr, "[rtlacam-sumo] tick %lld/%lld  at goal %d/%d  sim %.1f s  wall %.1f s (%.0fx real time)\n",
                 m_.ticks, cfg_.run.max_ticks, at_goal, ins_.num_agents(), m_.ticks * cfg_.run.tick_s, wall,
                 wall > 0 ? m_.ticks * cfg_.run.tick_s / wall : 0.0);
  }
}

void Run::stop_all()
{
  if (!sumo_ || !sumo_->running() || !cmd_) return;
  try {
    if (m_.error.empty()) m_.sim_s = sumo_->time();  // the run's time, without the stop
    const bool physical = cfg_.run.executor != "lockstep";
    const double dt = cfg_.sumo.step_length, decel = cfg_.fleet.vtype.decel;
    const std::vector<std::string> present = sumo_->vehicles();  // an AGV may be gone (the error)
    std::vector<std::string> ids;
    for (const std::string& id : cmd_->ids())
      if (std::find(present.begin(), present.end(), id) != present.end()) ids.push_back(id);
    // Braking from max_speed takes max_speed / (decel dt) steps; more if someone else sped one up.
    const int limit = static_cast<int>(std::ceil(1.5 * cfg_.fleet.vtype.max_speed / (decel * dt))) + 8;
    for (int s = 0; s <= limit; ++s) {
      bool moving = false;
      // One AGV that vanishes meanwhile (removed from outside) must not end the others'
      // stop: they kept their last speeds in a SUMO that outlived the controller.
      std::vector<std::string> gone;
      for (const std::string& id : ids) {
        try {
          const double v = sumo_->pose(id).speed;
          if (v <= 0) continue;
          moving = true;
          sumo_->set_speed(id, physical ? std::max(0.0, v - decel * dt) : 0.0);
        } catch (const std::exception&) {
          if (!sumo_->running()) throw;
          gone.push_back(id);
        }
      }
      for (const std::string& id : gone) ids.erase(std::find(ids.begin(), ids.end(), id));
      if (!moving) break;
      // Headings (adg): AGVs standing off their lane's angle keep their heading while the
      // others brake (SUMO would draw the lane's), a running turn stays where it got to.
      if (physical && cmd_->headings()) {
        const std::vector<uint8_t> hold(cmd_->ids().size(), 1);
        cmd_->orient(&hold);
      }
      if (c_.on_stop_step) c_.on_stop_step(*sumo_);
      sumo_->step();
      ++m_.end_stop_steps;
    }
  } catch (const std::exception&) {
    // SUMO is gone or refuses: nothing more can be commanded; the run's error stays.
  }
}

void Run::instance_bound()
{
  const planner::Graph& g = c_.map_.graph;
  // Lockstep turns only with the rotation solvers; the Driver turns whenever AGVs have
  // headings (fleet.turn_s too), a turn_s rounded to SUMO steps as the Commander does.
  const std::vector<int> none;
  const std::vector<double> lock =
      lockstep_alone_ticks(g, ins_.starts, ins_.goals, cfg_.planner.rotation_solver() ? start_headings_ : none);
  const double turn_step_s = std::lround(cfg_.fleet.turn_s / cfg_.sumo.step_length) * cfg_.sumo.step_length;
  const std::vector<double> phys =
      physical_alone_s(c_.map_, ins_.starts, ins_.goals, kinematics(), fastest_cell_speeds(c_.map_, cfg_.fleet.vtype.max_speed),
                       start_headings_, turn_step_s);
  m_.lockstep_bound_ticks = lock.empty() ? 0 : *std::max_element(lock.begin(), lock.end());
  m_.physical_bound_ticks = phys.empty() ? 0 : *std::max_element(phys.begin(), phys.end()) / cfg_.run.tick_s;
  m_.bound_ticks = cfg_.run.executor == "lockstep" ? m_.lockstep_bound_ticks : m_.physical_bound_ticks;
}

Metrics Run::execute()
{
  wall0_ = Clock::now();
  prepare();  // ConfigError propagates: nothing started yet
  c_.plan_.start(ins_.starts);
  // The physical bound (bound.hpp): lockstep moves a cell per tick; the others drive.
  alone_.emplace(cfg_.run.executor == "lockstep" ? nullptr : &c_.map_, kinematics());
  // Rotation: turns are steps (lockstep), or rest + turn_s each (physics).
  if (!start_headings_.empty())
    alone_->count_turns(c_.map_.graph, start_headings_, cfg_.run.executor == "lockstep" ? 0.0 : cfg_.fleet.turn_s);
  if (!tm_) instance_bound();
  if (tm_)  // lifelong: bounded memory (executed_plan.hpp)
    c_.plan_.bound(cfg_.output.plan_keep > 0 ? static_cast<size_t>(cfg_.output.plan_keep)
                                             : std::max<size_t>(64, (size_t{1} << 18) / static_cast<size_t>(ins_.num_agents())),
                   [this](const planner::Config& c) { alone_->add(c); },
                   &c_.map_.graph, cfg_.output.plan ? dir_ + "/.plan.txt.part" : "");
  loop0_ = last_progress_ = Clock::now();
  try {
    start_sumo();
    loop0_ = Clock::now();
    if (cfg_.run.executor != "lockstep")
      loop_adg();
    else
      loop_lockstep();
  } catch (const ControlError& e) {
    m_.error = e.what();
    ++m_.violations;
  } catch (const SumoError& e) {
    m_.error = e.what();
  } catch (const FleetError& e) {
    m_.error = e.what();
  } catch (const planner::OutputError& e) {
    m_.error = e.what();
  } catch (const std::exception& e) {
    m_.error = std::string("controller: ") + e.what();
  }
  if (!m_.solved) m_.signal = planner::stop_signal();
  m_.unsolvable = !m_.solved && proven_unsolvable();
  stop_all();  // every run end, a signal's included: all AGVs braked to rest before detaching
  finish();
  return m_;
}

}  // namespace controller
