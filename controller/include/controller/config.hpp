#pragma once
// Config: one controller run as read from YAML (see controller/README.md for the schema
// and defaults). Plain structs; load_config() validates everything that can be checked
// without the net (unknown keys, types, ranges, files), resolve_fleet() the rest
// (cells on the graph, enough free cells). Every error is one ConfigError line
// "file: key.path: what".
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "executor/delay_model.hpp"
#include "planner/rotation_settings.hpp"

namespace controller {

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A cell named in YAML: a vertex id, a station / junction id, or a SUMO lane position
// ({lane: L, pos: P}: the cell whose pose on L is nearest P). `key` is its key path.
struct CellRef {
  int vertex = -1;
  std::string name;
  std::string lane;
  double pos = 0;
  std::string key;
};

struct SumoOutputs {
  bool fcd = true, tripinfo = true, summary = true, collision = true;
};

struct SumoSection {
  std::string net;         // absolute after loading (relative paths are relative to the YAML)
  std::string additional;  // stations (optional)
  double step_length = 0.125;
  std::vector<std::string> extra_args;
  SumoOutputs outputs;
};

struct GridSection {
  double cell_length = 1.0;
  double tolerance = 0.01;
  bool snap = false;
  bool drop_one_way = false;
};

// The AGV vType. Lockstep (scheme S) derives maxSpeed (cell/tick) and emergencyDecel
// (vmax/dt); the adg executor drives with accel / decel / max_speed (m/s^2, m/s).
struct VType {
  double length = 0.8, width = 0.6, min_gap = 0.1, accel = 2.0, decel = 2.0;
  double max_speed = 1.0;
  bool physics_given = false;  // the YAML set accel, decel or max_speed (lock-step does not use them)
};

struct FleetSection {
  int count = 0;
  uint64_t seed = 0;
  bool random_starts = true;  // starts: random
  std::vector<CellRef> starts;
  VType vtype;
  // Seconds per quarter turn of an AGV standing on its cell: the rotation solvers plan turns
  // as actions; a cell solver's AGVs turn with their lanes (a reversal: an instant flip),
  // unless fleet.turn_s is given under adg / adg-follow (turn_in_place): then the Driver
  // turns them on their cells toward each move, as for the rotation solvers.
  double turn_s = 1.0;
  bool turn_in_place = false;
  bool headings(bool rotation_solver) const { return rotation_solver || turn_in_place; }
  // fleet.battery (lifelong only; tasks/battery.hpp): on when the key is present.
  // Fractions of capacity_wh: initial, threshold, critical, target. Chargers: the chargingStations of
  // sumo.additional, each at its `power` x `efficiency` (charge_w where it has no power).
  struct Battery {
    bool on = false;
    double capacity_wh = 100, initial = 1.0, per_m_wh = 0, per_turn_wh = 0, threshold = 0.3, target = 0.9;
    double critical = 0.1;   // below it mid-task: the task goes back, the AGV charges (< threshold; 0: off)
    double reserve_margin = 1.5;  // also low / critical below this x the energy to the nearest charger (0: off)
    bool rematch = true;          // AGVs on their way to chargers swap claims when that shortens their ways
    bool task_check = true;       // a task only if the charge covers it and the way on to a charger
    double charge_w = -1;    // -1: every chargingStation must give its power
    bool charging = true;    // false: drain only (no charging errands)
    int sample_ticks = 10;   // metrics.json battery.samples: min/mean/max charge every this many ticks
  } battery;
};

// planner.rotation: the options of the rotation solvers (pibt-rot, epibt, wppl), which plan
// forward / turn / wait actions for AGVs with a heading: planner::RotationSettings, the same
// keys, rules and messages as Python's rotation= dict (planner/rotation_settings.hpp), with
// the SUMO configs' defaults where they differ from the planners':
// - guidance: arrows for every rotation solver (parse_config; wppl since s37);
// - traffic_flow on for epibt (congestion-aware guide paths, traffic_flow.hpp);
// - epibt priority age (pibt-rot's rule), not the paper's distance: with distance, 16 AGVs
//   on the small lifelong warehouse swung between two cells in the one-cell aisles (0.007
//   errands/tick over 300 ticks; age 0.143).
struct RotationSection : planner::RotationSettings {
  RotationSection()
  {
    traffic_flow = true;
    priority = "age";
  }
};

struct PlannerSection {
  // rtlacam | naive | pibt | cspibt (pibt ordered by the policy) | pibt-rot | epibt | wppl
  // (the last three plan rotation actions: AGVs with a heading, fleet.turn_s per turn)
  std::string solver = "rtlacam";
  std::string policy;              // learned policy weights (absolute after loading); "" = none
  double budget_ms = 1.0;          // per SUMO step; 0 = no time limit
  uint64_t expansions = 0;         // per SUMO step; 0 = no limit (set it for deterministic runs)
  uint64_t seed = 0;
  // Planning before the first command, in ticks' budgets (steps_per_tick x budget_ms, or x
  // expansions), so the first move is planned as long as every later one (the paper's loop:
  // plan, then move). 0: the insertion step's one SUMO step. The default demo (16 AGVs,
  // one-cell aisles) locks in its cost with the first moves: executed SOC mean 265.4 with 0,
  // 251.8 with 1 (planner.free_first on, 40 runs; controller/README.md "Startup planning").
  int startup_ticks = 1;
  bool swap = true;
  bool keep_priorities = true;  // lifelong epochs keep PIBT priorities (planner::LacamOptions)
  bool refine = true;           // RT-LaCAM*: LaCAM* refinement after the first solution (false: the paper)
  // With refine: PIBT rollouts from the root inserted into the tree (LacamOptions::dive). The
  // agents follow LaCAM's first solution while refinement runs, and on a warehouse of one-cell
  // aisles that solution's backtracking costs 3-4x the bound; a rollout is a far cheaper path
  // (controller/README.md, "Dives").
  bool dive = true;
  // LNS stop cost (LacamOptions::lns_stop_cost): a planned move from rest (after a wait, or a
  // reversal) costs this many steps more in LNS's tie-break, so the refinement prefers plans
  // an AGV drives without stopping. 0: off.
  int stop_cost = 0;
  bool lns_moves = false;  // LacamOptions::lns_count_moves: LNS's tie-break counts moves, not the loss
  // PIBT's tie-break among equally short moves toward the goal (LacamOptions::free_first): a
  // free cell first, one whose AGV comes head-on or is parked on its goal last. On, as in the
  // CLI's and Python's RT-LaCAM* (session 44): shipped lifelong examples +2-16 % errands/tick
  // at 50 expansions per step, K lower on 6 of 9 (higher on large_warehouse_lifelong 123 ->
  // 171 and large_oneway_lifelong 199 -> 275); one-shot large_warehouse_agv makespan flat (gm
  // seeds 1-8: lockstep 1.03x, adg-follow 0.98x); the default demo's executed SOC with
  // startup planning 264.8 -> 251.8 (means of 40 runs). controller/README.md
  // "planner.free_first".
  bool free_first = true;
  // Highways (LacamOptions::highways, planner/highways.hpp): PIBT ranks a move against a
  // one-cell aisle's grain (aisles numbered across the grid, alternating) as 1 + this. 0: off.
  int highways = 0;
  // Slow lanes cost more in the distance tables PIBT and LaCAM rank moves by: a cell costs
  // ceil(v_fast / v_cell), v_cell its slowest lane's speed limit capped at the AGVs' top
  // speed, v_fast the fastest cell's (controller/lane_costs.hpp; planner Graph::set_move_costs).
  bool lane_costs = true;
  // Lifelong: the distance tables of the goals to come (the next errand of each task, a
  // round-robin agent's next task) are grown before the run and in each SUMO step's spare
  // budget, as rtlacam-lifelong --prefetch does (tasks::LifelongEpochs::prefetch). Off by
  // default: on the huge warehouse (1000 AGVs, 1 ms, 300 ticks) it cut the epoch starts'
  // lower-bound reads 2-9x but not the errands per tick (lockstep gm 0.996x of off,
  // adg-follow gm 0.912x, 5 pairs each; scripts/bench_prefetch.py, controller/README.md
  // "Prefetch").
  bool prefetch = false;
  RotationSection rotation;
  bool rotation_solver() const;  // solver plans rotation actions (planner::plans_rotation)
};

// one_shot: one goal per AGV, the run ends when all are there. lifelong: a stream of tasks
// (tasks/README.md), each a sequence of errand cells; the run ends at run.max_ticks.
struct TasksSection {
  std::string mode = "one_shot";  // one_shot | lifelong
  bool random_goals = true;       // one_shot
  uint64_t seed = 1;              // random goals / random tasks
  std::vector<CellRef> goals;     // one_shot

  // lifelong
  std::vector<CellRef> pickups, drops;  // empty: the stations of kind pickup / drop
  std::string pickups_key = "tasks.pickups", drops_key = "tasks.drops";
  bool random_tasks = true;             // tasks.random (default) or tasks.list
  int count = 100;                      // random: tasks in the (cyclic) stream
  int errands = 2;                      // random: errands per task: pick-up, drop, pick-up, ...
  std::vector<std::vector<CellRef>> list;  // listed tasks: errand cells
  std::string assignment = "roundrobin";   // roundrobin | pool
  std::string assigner = "greedy";         // pool: greedy | hungarian
  int pool_size = 0;                       // pool: revealed tasks; 0 = ceil(1.5 x fleet.count)
  int k_nearest = 32;                      // hungarian: candidate tasks per AGV
  bool reassign = false;                   // pool: a nearer free AGV may take an unopened task
  // Priority hints to the planner (tasks/urgency.hpp): low batteries; stalled errands
  // (1 on, 0 off, -1 auto: only with station queues -- without them the hinted crowd wedges
  // the dead-end stubs: controller/README.md "Priority hints").
  bool urgency_battery = true;
  int urgency_stalls = -1;
  // Station queues (tasks/station_queues.hpp): AGVs admitted to one station at once (0: off),
  // queue cells per station, pool admission limit (0: capacity + length, -1: none).
  int queue_capacity = 0, queue_length = 4, queue_admission = 0;
  int queue_clear_after = 0;  // tasks::QueueOptions::clear_after (0: off)
  int queue_jam_after = 0;    // tasks::QueueOptions::jam_after (0: off)
  bool queue_one_way = false; // tasks::QueueOptions::one_way
  bool queue_in_line = false;  // tasks::QueueOptions::in_line (default true with solver epibt: config.cpp)
  bool queue_leavers_first = false;  // tasks::QueueOptions::leavers_first
  bool queue_idle_clear = false;     // tasks::QueueOptions::idle_clear (off by default: docs/twin_bench.md s38-20f)
  bool queue_fifo = true;  // beyond a queue, the oldest request first (tasks::QueueOptions::fifo)
  // Parking (tasks/parking.hpp): off, the sumo.additional parkingAreas (parking_auto), or a list.
  bool parking = false, parking_auto = false;
  std::vector<CellRef> parking_cells;
  std::string log = "lifelong.json";       // in output.dir
  // Stall handover (tasks::UrgencyOptions::swap_after, tasks/task_pool.hpp): a pool errand not
  // yet opened and stalled this many ticks passes to a nearer AGV heading for the same cell (0: off).
  int urgency_swap_after = 0;
  // Head hints (tasks::UrgencyOptions::head_after): per errand cell, the AGV whose errand has
  // stalled longest (if >= this many ticks) gets planner priority (0: off).
  int urgency_head_after = 0;
  // Station load in the pool's matching (tasks::UrgencyOptions::load_cost): moves a task costs
  // per task already held with an errand left at each of its errand cells (0: off).
  int urgency_load_cost = 0;
  // Foreign-pocket cost (tasks::UrgencyOptions::pocket_cost): moves PIBT adds to an AGV's move
  // into a dead-end station stub that is not its errand's (0: off).
  int urgency_pocket_cost = 0;
  bool urgency_drop_hints = false;  // tasks::UrgencyOptions::drop_hints
  // Stub-mouth cost (tasks/stub_mouths.hpp; 0: off): moves the distance tables add to a move
  // onto the cell where a station's dead-end stub joins the net.
  int urgency_mouth_cost = 0;
  bool urgency_sticky = false;  // tasks::UrgencyOptions::sticky
  int urgency_escalate_after = 0;  // tasks::UrgencyOptions::escalate_after (escalation.hpp; 0: off)

  bool lifelong() const { return mode == "lifelong"; }
};

struct RunSection {
  double tick_s = 1.0;
  long long max_ticks = 1000;
  std::string backend = "libsumo";  // libsumo | traci
  bool gui = false;                  // sumo-gui through TraCI
  double gui_delay_ms = 100;         // sumo-gui's --delay (a watchable pace; 0 = flat out)
  int port = 0;                      // traci: connect to a running SUMO instead of starting one
  int order = 0;                     // run.port: this client's TraCI order in a SUMO of several clients (sumo --num-clients N); 0: the only one
  double progress_s = 2.0;           // wall seconds between progress lines; 0 = none
  std::string executor = "lockstep"; // lockstep (all AGVs one cell per tick) | adg | adg-follow (executor/)
  int window = 4;                    // adg: committed configurations ahead of the slowest AGV (at most)
  int drain = 0;                     // adg: commit again once fewer than this are left (1..window; 0: window)
  // adg, lifelong: the task layer runs on the committed plan, not on the executed cells: an
  // errand is done for planning when the plan reaches it, and counted when the AGV executes
  // it (run.hpp "Plan completions"). Not with batteries, rules or rotation solvers (their
  // goals need the AGV there in time): those keep the executed cells.
  bool plan_completions = true;
  bool replan_on_stuck = true;       // adg: reroute the others around a stuck AGV (stuck_replan.hpp)
  double stuck_after_s = 5.0;        // adg: no progress for this long while it may go = stuck
  // adg: ... or twice the longest stall so far that ended by itself, if longer (StuckWatch learn)
  bool stuck_learn = true;
  // adg-follow flow (controller/driver.hpp DriveParams; switches for tests and benches):
  bool relative_braking = true;      // count on a leader's sure travel when following
  // The hardest a leader may be stopped (by itself or from outside: a bumper, a person), m/s^2,
  // that its followers must survive: its sure travel is its braking distance at this decel.
  // 0: the vType's decel (no AGV brakes harder by itself).
  double leader_decel = 0;
  bool same_step_starts = true;      // a move released by another start in a step starts in it
  // adg / adg-follow: a ready AGV passes a cell before a late one (Adg::try_switch); 0: off,
  // k >= 1: the late one has at least k moves to make before it enters the cell.
  int switch_passages = 0;
  bool chain_to_end = true;          // a chained move's leader gap measured from the move's end
  bool gap_handover = true;          // a follower may reach the cell before its leader arrives (body gap only)
  // adg, cell plans (one-shot and lifelong; not rotation solvers): commits held back this many
  // configurations (beyond run.window) to cut an AGV's out-and-back u -> v -> u into waits on u
  // when nobody else uses u meanwhile (executor/out_and_back.hpp); lifelong: never through the
  // AGV's goal; 0: off.
  int out_and_back = 8;
  // With out_and_back: cut every excursion u -> ... -> u (u free meanwhile), not only u -> v -> u.
  bool cut_loops = true;
  // With out_and_back and rules (controller/rules.hpp): cut there too (nobody else in u's
  // one-at-a-time zone meanwhile either). Off by default: measured neutral on small_rules
  // (one-shot and lifelong, session 34), so rules runs keep their plans.
  bool out_and_back_rules = false;
  // Lane speed limits: lockstep stretches a step over the ticks its slowest move needs at its
  // lane's speed; adg: the Driver's DriveParams::lane_speeds. false: a cell per tick regardless.
  bool lane_speeds = true;
  // Lifelong: an epoch start stays within the next SUMO step's planner budget (controller/src/run.cpp
  // Run::epoch_start), and lockstep runs it at the tick's start (switch for tests and benches).
  bool epoch_in_budget = true;
};

// Delays (executor/delay_model.hpp), durations in seconds in the YAML, ticks here.
struct DelaysSection {
  executor::DelaySpec spec;
  bool any() const { return spec.kind != "none" || !spec.slow.empty() || !spec.stuck.empty(); }
};

struct OutputSection {
  std::string dir = "out/run";  // relative to the working directory
  bool plan = true;
  // Lifelong: executed configurations kept in memory beyond those a replan may rewrite;
  // older ones are written to plan.txt as the run goes (controller/executed_plan.hpp).
  // 0: 2^18 vertex ids' worth (1 MB), at least 64 configurations.
  int plan_keep = 0;
  bool congestion = true;  // congestion.png (congestion.hpp)
  int queue_trace = 0;     // lifelong with station queues: queue_trace.txt every N ticks (tasks/queue_trace.hpp); 0 = none
  std::vector<double> gui_snapshots;  // run.gui: sumo-gui writes gui_<t>.png at these simulated seconds
};

// Warehouse traffic rules (rules.hpp): closures and one-at-a-time zones from the YAML; the
// SUMO forms (rerouter closingReroute intervals, rtlacam.zone polygons) come from
// sumo.additional (rules.sumo), lane permissions changed over TraCI from polling
// (rules.watch_lanes). Cell solvers only; every executor (lockstep, adg, adg-follow).
struct RuleClosure {
  std::string key;  // rules.closures[i]
  std::vector<std::string> lanes, edges;
  std::vector<CellRef> cells;
  double begin = 0, end = 1e300;  // s (end omitted: the rest of the run)
};

struct RuleZone {
  std::string key;  // rules.zones[i]
  std::string id;
  std::vector<std::string> lanes, edges;
  std::vector<CellRef> cells;
};

struct RulesSection {
  bool sumo = true;          // read rerouters / zone polygons of sumo.additional
  int watch_lanes = -1;      // poll the AGV lanes' permissions every tick; -1: lockstep with libsumo only
  std::vector<RuleClosure> closures;
  std::vector<RuleZone> zones;
  bool enforce_closures = true;  // false: the planner ignores closures (Safety still checks them)
  bool enforce_zones = true;     // false: no zone admission (Safety still checks the zones)
  // The cell solvers plan the zones too (planner/zones.hpp): no step of theirs puts two AGVs
  // in a zone, so lock-step admission never holds anyone back and the search is never
  // restarted for a zone. 1 / 0 / -1 = auto: on with run.executor lockstep, where admission's
  // restarts (each forgets the search) left 5 of 11 small_rules instances unsolved after
  // 1500 ticks (all 11 solved with it); off under adg / adg-follow, whose zone mutex holds
  // entrants without restarting the search and solved all 11 either way (makespan on/off gm
  // 1.04) (docs/closed_loop_bench.md "Zones in the planner").
  int plan_zones = -1;
  bool zones_in_planner(const std::string& executor) const { return plan_zones < 0 ? executor == "lockstep" : plan_zones != 0; }
  // Lifelong pool: a task whose next errand a closure cuts off goes back to the pool and the
  // AGV takes one it can reach (tasks/task_manager.hpp); false: the AGV waits for the closure.
  bool reassign = true;
};

struct Config {
  std::string path;  // the YAML file
  SumoSection sumo;
  GridSection grid;
  FleetSection fleet;
  PlannerSection planner;
  TasksSection tasks;
  RunSection run;
  DelaysSection delays;
  OutputSection output;
  RulesSection rules;

  int steps_per_tick() const;  // tick_s / step_length (validated to be a whole number)
};

Config load_config(const std::string& path);
// The checks that follow from planner.solver (policy, executor, fleet.turn_s); parse_config
// runs them, and an app that overrides the solver runs them again.
void check_solver(const Config& c);
// The same from YAML text; relative paths resolve against `base_dir`.
Config parse_config(const std::string& yaml, const std::string& name, const std::string& base_dir);

}  // namespace controller
