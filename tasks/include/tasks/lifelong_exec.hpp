#pragma once
// Lifelong runs through the executor (executor/graph_execution.hpp): the same task layer
// and planner as run_lifelong, but the agents execute what the planner commits under
// delays -- lockstep (all wait for the slowest) or the action dependency graph (each agent
// on its own). Errands complete where the agents really are (the executed positions); on
// completions the planner gets new goals at its committed configuration, which the agents
// reach once the committed window is executed. A delayed agent stays put. It is a
// LifelongRun (lifelong_run.hpp) with LifelongOptions::graph_execution: the one lifelong loop.
#include "executor/delay_model.hpp"
#include "executor/graph_execution.hpp"
#include "tasks/lifelong_runner.hpp"

namespace tasks {

struct LifelongExecResult {
  LifelongResult life;
  executor::ExecStats exec;
  long long max_gap = 0;  // longest run of ticks without an errand completion
};

LifelongExecResult run_lifelong_exec(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                                     const std::string& solver, uint64_t seed, const LifelongOptions& opt,
                                     const executor::DelaySpec& delays, const executor::ExecOptions& exec);

}  // namespace tasks
