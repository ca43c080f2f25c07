#pragma once
// Metrics of one controller run, written as metrics.json in the output directory
// (also when the run stops on an error: what happened so far, plus the error line).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "controller/commander.hpp"
#include "controller/fleet_view.hpp"
#include "planner/latency.hpp"
#include "tasks/errand_stalls.hpp"

namespace controller {

// Summary of a sample of durations in milliseconds (one p99 definition for all layers).
using Latency = planner::Latency;

struct Metrics {
  std::string config, net, backend, solver, error;  // error: "" when the run was clean
  std::string policy;           // planner.policy weights file, "" = none
  int signal = 0;               // SIGINT / SIGTERM ended the run early (outputs still complete)
  bool solved = false;
  bool unsolvable = false;      // one-shot: the search proved no solution exists (the run ended then)          // every AGV on its goal (one-shot)
  int agents = 0, cells = 0;
  long long ticks = 0;          // executed ticks (MAPF steps)
  long long makespan = 0, soc = 0, soc_lb = 0;
  long long violations = 0;     // validator / collision / teleport / arrival / lost AGV
  uint64_t expansions = 0;
  double tick_s = 0, step_length = 0, sim_s = 0, wall_s = 0, budget_ms = 0;
  double loop_s = 0;            // wall time of the tick loop (start-up and insertion excluded)
  Latency planner_ms_per_step;  // one search(budget) call per SUMO step
  Latency planner_cpu_ms_per_step;  // thread CPU of all planner work per SUMO step (commits, epochs, replans too)
  Latency planner_ms_per_tick;  // sum over the steps of a tick
  double planner_startup_ms = 0, planner_startup_cpu_ms = 0;  // the search before the first command (wall, thread CPU)
  uint64_t planner_startup_expansions = 0;                      // and its expansions
  Latency sumo_ms_per_step;     // SUMO's own step (inside the back end)
  Latency control_ms_per_tick;  // commands + verification
  CommandStats commands;

  // Executor (run.executor) and delays. teleports_or_jumps = SUMO teleports are errors
  // (the run stops), so this is moveTo jumps + re-syncs: must be 0.
  std::string executor = "lockstep";
  int window = 1;
  long long dependency_waits = 0;   // adg: agent-steps a committed move waited for its dependencies
  long long lockstep_waits = 0;     // lockstep: ticks all AGVs waited for a stopped one
  long long lockstep_paced = 0;     // lockstep: ticks in which a mover fell behind in SUMO (an outside stop)
  long long lockstep_paced_ticks = 0;  // lockstep: ticks added to them until it arrived
  long long delay_agent_ticks = 0;  // agent-ticks stopped by the delay model
  long long delay_stops = 0;        // stops injected
  long long chained = 0;            // adg: moves started without stopping in between
  long long switches = 0;           // adg: passages reordered (run.switch_passages)
  long long out_and_backs = 0;      // adg: out-and-backs cut from the plan (run.out_and_back)
  long long plan_completions = 0;   // adg lifelong, run.plan_completions: errands the plan reached (executed or not)
  long long plan_debts = 0;         // of them, cut off by a stuck replan before the AGV got there (run.hpp)
  long long followed = 0;           // adg-follow: moves started while the cell's previous occupant was still leaving it
  long long safety_checks = 0;      // SUMO steps checked by Safety (overlap / on path)
  long long commits = 0;            // configurations the planner committed
  long long replans = 0;            // adg: replans around stuck AGVs and after their recovery
  long long stuck_events = 0;       // adg: AGVs found stuck (then made immobile)
  long long searches_skipped = 0;   // SUMO steps whose budget went to a replan or epoch start before the search
  std::vector<double> goal_s;       // adg, one-shot: sim time each AGV reached its goal for good (-1: not)
  Latency executor_ms_per_step;     // adg: driver (starts, speeds, arrivals) + safety
  ViewStats view;                   // fleet_view.hpp: colour and goal-marker calls, their ms
  double congestion_ms = 0;         // counting + writing congestion.png
  // adg: agent-steps by what bounds the speed (DriveStats::Time): cruise, accel, follow,
  // lane, end, start_wait.
  long long time_cruise = 0, time_accel = 0, time_follow = 0, time_lane = 0, time_end = 0, time_start_wait = 0;
  double overshoot_m = 0;           // adg: most a speed command ever drove past a stopping point (0: never)
  long long turn_steps = 0;         // adg with headings: agent-steps turning toward the next move (driver.hpp)
  // adg: agent-steps up to each AGV's last arrival by category (DriveStats::split, names as
  // DriveStats::split_name), and the moves started from rest: metrics.json executor.split.
  std::vector<std::pair<std::string, long long>> split;
  long long starts_from_rest = 0, starved_starts = 0, starved_steps = 0;
  // Lane speeds (metrics.json "lane_speeds" when either is > 0): cells a slow lane makes
  // costlier for the planner (planner.lane_costs), ticks lockstep added to keep to lane
  // speeds (run.lane_speeds: steps stretched beyond their ticks without them).
  long long costly_cells = 0, lane_ticks = 0;
  // Traffic rules (rules.hpp), written as metrics.json "rules" when a run has them (also
  // when it only watches lanes: libsumo lockstep runs by default).
  struct RuleStats {
    bool active = false;
    long long closure_changes = 0;  // tick boundaries where the closed cells changed
    long long replans = 0;          // planner restarts (closures, zone occupancy, held entrants)
    long long zone_holds = 0;       // AGV-ticks held at a zone entry by the admission
    long long waits = 0;            // AGV-ticks an AGV waited for an unreachable goal
    int max_closed = 0;             // most cells closed at once
    long long checks = 0;           // SUMO steps RuleCheck checked
    double poll_ms = 0;             // wall ms in Rules::update (closure schedule + lane polling), all ticks
  } rules;
  long long max_errand_ticks = 0;   // lifelong: longest any AGV kept one goal, idle ones too (open ones to the end)
  // Lifelong: errands of busy AGVs only (tasks/errand_stalls.hpp): open ticks (assignment
  // to completion) and stall ticks (longest stretch without getting closer), max and p99;
  // metrics.json lifelong.errandTicks / stallTicks. K = stalls.max_stall.
  tasks::ErrandStalls::Summary stalls;
  long long end_stop_steps = 0;     // SUMO steps the stop at the run's end took (all AGVs at rest after)
  // One-shot: the instance bound (instance_bound.hpp), in ticks, fixed by the instance (the
  // same for every executor and plan): the slowest AGV alone on a shortest way, under physics
  // (physical_bound_ticks) and in lockstep (lockstep_bound_ticks); bound_ticks is the one of
  // this run's executor, makespan_over_bound its ratio.
  double bound_ticks = 0, physical_bound_ticks = 0, lockstep_bound_ticks = 0;
  double makespan_over_bound() const { return bound_ticks > 0 ? makespan / bound_ticks : 0.0; }
  // The plan's bound (bound.hpp), in ticks: every AGV alone on the path it was planned; it
  // moves with the plan, and the plan with the execution. One-shot, the slowest AGV; lifelong,
  // the mean over the AGVs (throughput bound = tasks / that mean).
  double plan_bound_ticks = 0;
  double makespan_over_plan_bound() const { return plan_bound_ticks > 0 ? makespan / plan_bound_ticks : 0.0; }
  double throughput_bound() const { return plan_bound_ticks > 0 ? tasks_finished / plan_bound_ticks : 0.0; }
  double free_flow_bound = 0;  // lifelong: errands per tick with every AGV alone (tasks/free_flow.hpp), every errand handed out
  double free_flow_bound_finished = 0;  // the same over the finished errands only (biased to the short ones)

  // Lifelong runs (tasks.mode: lifelong); the full log is tasks.log beside metrics.json.
  std::string mode = "one_shot", assignment;
  long long errands_finished = 0, tasks_finished = 0, epochs = 0;
  // Distance reads of the epoch starts' set_goals answered with a lower bound because the
  // step's deadline had passed (run.epoch_in_budget; 0 with it off: those reads are exact),
  // metrics.json lifelong.epochDistEstimates.
  long long epoch_estimates = 0;
  // planner.prefetch: BFS vertices grown ahead of their queries in the cell solvers' shared
  // distance tables (before the run and in the SUMO steps' spare budget), metrics.json
  // lifelong.precomputePops (0 with it off).
  long long precompute_pops = 0;
  // Lifelong with closures: tasks an AGV handed back because a closure cut it off its next
  // errand (tasks/task_manager.hpp), metrics.json lifelong.reassignedForClosure.
  long long reassigned_for_closure = 0;
  // Station queues and parking (tasks.queues, tasks.parking), counted at every tick's end
  // over the task file's errand cells whether queues are on or not: the most AGVs heading
  // for one station's cell at once, AGV-ticks spent standing on a queue goal (busy, not
  // heading for its errand), and at the end the idle AGVs and those of them on a parking cell.
  int max_heading = 0;
  long long queued_ticks = 0;
  long clearings = 0;  // station pockets cleared (tasks.queues.clear_after, jam_after)
  long jam_clearings = 0;  // of those, jams cleared (tasks.queues.jam_after)
  long clearing_steps = 0;   // steps stations spent clearing, summed over stations
  int longest_clearing = 0;  // the longest clearing in steps
  int idle_at_end = 0, parked_at_end = 0;
  long long idle_ticks = 0, parked_ticks = 0;  // AGV-ticks without a task, and of those on a parking cell
  // fleet.battery (tasks/battery.hpp), metrics.json "battery": charging errands begun,
  // AGVs whose charge reached 0 (must be 0), the share of AGV-ticks spent charging on a
  // charger, the lowest charge any AGV had (fraction), and every sample_ticks ticks the
  // fleet's min / mean / max charge (fractions of capacity); dropped_mid_task: tasks handed
  // back below the critical charge (the AGV went to charge at once).
  struct BatteryStats {
    bool active = false, charging = true;
    double capacity_wh = 0;
    long long errands = 0, dropped_mid_task = 0;
    int ran_empty = 0;
    double charging_share = 0, min_charge = 1;
    struct Sample {
      long long tick;
      double min, mean, max;
    };
    std::vector<Sample> samples;
  } battery;
  double throughput() const { return ticks > 0 ? static_cast<double>(tasks_finished) / ticks : 0.0; }
  double errand_throughput() const { return ticks > 0 ? static_cast<double>(errands_finished) / ticks : 0.0; }

  // Wall milliseconds per simulated second in the tick loop: all, SUMO's own steps
  // (inside the back end), the controller (everything else: planner + commands +
  // verification + event checks), the planner alone. ratio = controller / sumo.
  struct PerSimSecond {
    double wall_ms = 0, sumo_ms = 0, controller_ms = 0, planner_ms = 0, control_ms = 0, ratio = 0;
  };
  PerSimSecond per_sim_second() const;

  nlohmann::json to_json() const;
};

}  // namespace controller
