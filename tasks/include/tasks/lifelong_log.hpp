#pragma once
// The JSON logs of a lifelong run.
//
// lifelong_log: the summary every executor writes (rtlacam-lifelong, the SUMO controller).
// Names follow LoRR where the quantity is LoRR's: actionModel ("MAPF" = grid4, "MAPF_T" =
// rotation), teamSize, numTaskFinished, makespan, plannerTimes (seconds per step, a list),
// events [t, agent, task, errands done] (LoRR 2024: the 4th field is the index of the next
// errand, so 1 for a task's first errand). Ours, one name per quantity: taskThroughput,
// errandThroughput (per step), plannerTimeStats (ms: mean, p50, p99, max), numErrandFinished.
//
// lorr_log: lifelong_log plus every field PlanViz (script/run.py) and the LoRR scorer read,
// in the format of the run's semantics:
//   pool (2024): version "2024 LoRR", start, actualPaths, plannerPaths, errors, events (flat,
//     as above), tasks [id, revealed, [row, col, ...]], actualSchedule / plannerSchedule
//     ("t:task,..." per agent; t = the step whose move first serves the assignment).
//   roundrobin (2023): version "2023 LoRR", start, actualPaths, plannerPaths, errors, events
//     per agent [task, t, "assigned" | "finished"], tasks [id, row, col]; task ids are
//     LoRR's (a counter in assignment order), not our sequence numbers.
// Paths are action letters joined by commas: F/R/C/W (MAPF_T) or PlanViz's U/D/L/R/W (MAPF).
#include <nlohmann/json.hpp>
#include <string>

#include "tasks/lifelong_runner.hpp"

namespace tasks {

struct RunInfo {          // what was run, for the log
  std::string problem, solver, mode, assigner;
  int team_size = 0;
  double budget_ms = 0;
  uint64_t seed = 0;
};

nlohmann::json lifelong_log(const RunInfo& info, const LifelongResult& r);

// Needs r.actions (LifelongOptions::record_actions) and a grid graph.
nlohmann::json lorr_log(const RunInfo& info, const LifelongResult& r, const TaskManager& tasks, const planner::Graph& g);

// Pool mode: `reassign` (nearer free agents may take unopened tasks) and `numReassignments` (times a task
// changed agent). Nothing for other modes.
void add_task_fields(nlohmann::json& j, const TaskManager& tasks);

// run_lifelong's end-of-run check (LifelongResult::unreachable_goals, unsolvable_epoch) as
// "unreachableGoals" and "unsolvableEpoch" (rtlacam-lifelong, Python's lifelong()), and the
// one-line stderr warning for it ("" when neither): such a run used to end silently with rc 0.
void add_stuck_fields(nlohmann::json& j, const LifelongResult& r);
std::string stuck_warning(const LifelongResult& r);

}  // namespace tasks
