#pragma once
// The JSON log of a lifelong run. Field names follow the LoRR output where they mean the
// same (actionModel, teamSize, numTaskFinished, makespan, events); the rest is ours.
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

// Pool mode: `reassign` (nearer free agents may take unopened tasks) and `numReassignments` (times a task
// changed agent). Nothing for other modes.
void add_task_fields(nlohmann::json& j, const TaskManager& tasks);

}  // namespace tasks
