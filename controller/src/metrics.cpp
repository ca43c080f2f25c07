#include "controller/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "planner/stop_signal.hpp"

namespace controller {

static nlohmann::json latency_json(const Latency& l)
{
  return {{"count", l.count}, {"mean", l.mean}, {"p50", l.p50}, {"p99", l.p99}, {"max", l.max}};
}

Metrics::PerSimSecond Metrics::per_sim_second() const
{
  PerSimSecond p;
  const double sim = ticks * tick_s;
  if (sim <= 0) return p;
  p.wall_ms = loop_s * 1000 / sim;
  p.sumo_ms = sumo_ms_per_step.mean * sumo_ms_per_step.count / sim;
  p.planner_ms = planner_ms_per_step.mean * planner_ms_per_step.count / sim;
  p.controller_ms = std::max(0.0, p.wall_ms - p.sumo_ms);
  p.control_ms = std::max(0.0, p.controller_ms - p.planner_ms);
  p.ratio = p.sumo_ms > 0 ? p.controller_ms / p.sumo_ms : 0.0;
  return p;
}

nlohmann::json Metrics::to_json() const
{
  nlohmann::json j;
  j["config"] = config;
  j["net"] = net;
  j["backend"] = backend;
  j["solver"] = solver;
  j["policy"] = policy;
  j["error"] = error;
  j["interrupted"] = signal ? planner::signal_name(signal) : "";
  j["unsolvable"] = unsolvable;
  j["mode"] = mode;
  if (mode == "lifelong")
    j["lifelong"] = {{"assignment", assignment},
                     {"numTaskFinished", tasks_finished},
                     {"numErrandFinished", errands_finished},
                     {"throughput", throughput()},
                     {"errandThroughput", errand_throughput()},
                     {"epochs", epochs}};
  if (mode == "lifelong") {
    j["lifelong"]["throughputBound"] = throughput_bound();
    j["lifelong"]["maxErrandTicks"] = max_errand_ticks;
    j["lifelong"]["errandTicks"] = {{"max", stalls.max_open}, {"p99", stalls.p99_open}, {"errands", stalls.errands}};
    j["lifelong"]["stallTicks"] = {{"max", stalls.max_stall}, {"p99", stalls.p99_stall}};
    j["lifelong"]["reassignedForClosure"] = reassigned_for_closure;
    j["lifelong"]["epochDistEstimates"] = epoch_estimates;
    j["lifelong"]["precomputePops"] = precompute_pops;
    j["lifelong"]["throughputOverBound"] = throughput_bound() > 0 ? throughput() / throughput_bound() : 0.0;
    // Every AGV alone on its errand sequence, along shortest paths (tasks/free_flow.hpp): over
    // the finished errands and those open at the end; the finished ones alone beside it.
    j["lifelong"]["freeFlowBound"] = free_flow_bound;
    j["lifelong"]["freeFlowBoundFinishedOnly"] = free_flow_bound_finished;
    j["lifelong"]["errandThroughputOverFreeFlow"] = free_flow_bound > 0 ? errand_throughput() / free_flow_bound : 0.0;
    j["lifelong"]["queues"] = {{"maxHeading", max_heading}, {"queuedTicks", queued_ticks}, {"clearings", clearings}, {"jamClearings", jam_clearings},
                                   {"clearingSteps", clearing_steps}, {"longestClearing", longest_clearing}};
    j["lifelong"]["parking"] = {{"idleAtEnd", idle_at_end}, {"parkedAtEnd", parked_at_end},
                                  {"idleTicks", idle_ticks}, {"parkedTicks", parked_ticks}};
  }
  if (battery.active) {
    nlohmann::json samples = nlohmann::json::array();
    for (const BatteryStats::Sample& x : battery.samples) samples.push_back({{"tick", x.tick}, {"min", x.min}, {"mean", x.mean}, {"max", x.max}});
    j["battery"] = {{"capacity_wh", battery.capacity_wh}, {"charging", battery.charging}, {"charging_errands", battery.errands},
                    {"dropped_mid_task", battery.dropped_mid_task},
                    {"ran_empty", battery.ran_empty}, {"charging_share", battery.charging_share},
                    {"min_charge", battery.min_charge}, {"samples", samples}};
  }
  j["plan_bound_ticks"] = plan_bound_ticks;
  if (mode != "lifelong") {
    j["bound_ticks"] = bound_ticks;
    j["makespan_over_bound"] = makespan_over_bound();
    j["physical_bound_ticks"] = physical_bound_ticks;
    j["lockstep_bound_ticks"] = lockstep_bound_ticks;
    j["makespan_over_plan_bound"] = makespan_over_plan_bound();
  }
  j["solved"] = solved;
  j["agents"] = agents;
  j["cells"] = cells;
  j["ticks"] = ticks;
  j["makespan"] = makespan;
  j["soc"] = soc;
  j["soc_lb"] = soc_lb;
  j["violations"] = violations;
  j["expansions"] = expansions;
  j["tick_s"] = tick_s;
  j["step_length"] = step_length;
  j["budget_ms_per_step"] = budget_ms;
  j["sim_s"] = sim_s;
  j["wall_s"] = wall_s;
  j["real_time_factor"] = wall_s > 0 ? sim_s / wall_s : 0.0;
  j["loop_s"] = loop_s;
  const PerSimSecond p = per_sim_second();
  j["ms_per_sim_s"] = {{"wall", p.wall_ms},
                       {"sumo", p.sumo_ms},
                       {"controller", p.controller_ms},
                       {"planner", p.planner_ms},
                       {"control", p.control_ms}};
  j["controller_to_sumo_ratio"] = p.ratio;
  j["planner_ms_per_step"] = latency_json(planner_ms_per_step);
  j["planner_cpu_ms_per_step"] = latency_json(planner_cpu_ms_per_step);
  j["planner_ms_per_tick"] = latency_json(planner_ms_per_tick);
  j["planner_startup"] = {{"wall_ms", planner_startup_ms}, {"cpu_ms", planner_startup_cpu_ms}, {"expansions", planner_startup_expansions}};
  j["sumo_ms_per_step"] = latency_json(sumo_ms_per_step);
  j["control_ms_per_tick"] = latency_json(control_ms_per_tick);
  j["commands"] = {{"total", commands.total()},
                   {"set_speed", commands.speed},
                   {"set_route", commands.route},
                   {"move_to", commands.move_to},
                   {"set_angle", commands.angle},
                   {"jumps", commands.jumps}};
  j["quarter_turns"] = commands.quarter_turns;
  j["resyncs"] = commands.resyncs;
  j["turns_in_place"] = commands.turns;
  // Of those, reversals SUMO shows as an instant 180-degree flip of the AGV (no heading:
  // a cell solver without fleet.turn_s); with headings the AGV has turned first.
  j["instant_flips"] = commands.flips;
  j["teleports_or_jumps"] = commands.jumps + commands.resyncs;
  j["collisions"] = error.find("overlap") != std::string::npos || error.find("colliding") != std::string::npos ? 1 : 0;
  j["executor"] = {{"mode", executor},
                   {"window", window},
                   {"commits", commits},
                   {"replans", replans},
                   {"stuck_events", stuck_events},
                   {"searches_skipped", searches_skipped},
                   {"dependency_waits", dependency_waits},
                   {"lockstep_waits", lockstep_waits},
                   {"lockstep_paced", lockstep_paced},
                   {"lockstep_paced_ticks", lockstep_paced_ticks},
                   {"delay_agent_ticks", delay_agent_ticks},
                   {"delay_stops", delay_stops},
                   {"chained", chained},
                   {"switches", switches},
                   {"out_and_backs", out_and_backs},
                   {"plan_completions", plan_completions},
                   {"plan_debts", plan_debts},
                   {"followed", followed},
                   {"time", {{"cruise", time_cruise}, {"accel", time_accel}, {"follow", time_follow},
                             {"lane", time_lane}, {"end", time_end}, {"start_wait", time_start_wait},
                             {"dependency", dependency_waits}}},
                   {"safety_checks", safety_checks},
                   {"overshoot_m", overshoot_m},
                   {"end_stop_steps", end_stop_steps},
                   {"ms_per_step", latency_json(executor_ms_per_step)}};
  if (turn_steps > 0) j["executor"]["turn_steps"] = turn_steps;  // adg with headings only
  if (!split.empty()) {  // adg only
    nlohmann::json s = nlohmann::json::object();
    for (const auto& [k, n] : split) s[k] = n;
    j["executor"]["split"] = s;
    j["executor"]["starts_from_rest"] = starts_from_rest;
    j["executor"]["starved"] = {{"starts", starved_starts}, {"steps", starved_steps}};
  }
  if (costly_cells > 0 || lane_ticks > 0) j["lane_speeds"] = {{"costly_cells", costly_cells}, {"lockstep_ticks", lane_ticks}};
  if (!goal_s.empty()) j["executor"]["goal_s"] = goal_s;  // adg one-shot: per AGV, -1 = not there
  if (rules.active)
    j["rules"] = {{"closure_changes", rules.closure_changes}, {"replans", rules.replans}, {"zone_holds", rules.zone_holds},
                  {"waits", rules.waits}, {"max_closed", rules.max_closed}, {"checks", rules.checks},
                  {"poll_ms", rules.poll_ms}};
  j["max_position_error_m"] = commands.max_error;
  // What the display costs (fleet_view.hpp, congestion.hpp): calls are sent on changes only.
  j["view"] = {{"colour_calls", view.colour_calls},
               {"goal_calls", view.goal_calls},
               {"ms", view.ms},
               {"congestion_ms", congestion_ms}};
  return j;
}

}  // namespace controller
