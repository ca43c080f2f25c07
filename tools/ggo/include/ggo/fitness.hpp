#pragma once
// Fitness of a guidance for GGO: errands per step of a lifelong epibt run (roundrobin, the
// LoRR 2023 setting), in-process (no app start, no JSON). Deterministic: epibt runs a fixed
// number of LNS rounds, and the step budget (1 s) is far above its CPU time on these maps
// (<= 40 ms per step), so no step reaches its deadline and nothing depends on the clock or
// the load: the same guidance and seed give the same number.
#include <memory>
#include <string>

#include "planner/rotation/epibt.hpp"
#include "planner/graph.hpp"
#include "planner/rotation/guidance.hpp"
#include "tasks/task_manager.hpp"

namespace ggo {

struct Problem {
  std::string name;      // e.g. MR23-I-05
  planner::Graph g;
  planner::Config starts;
  std::shared_ptr<const tasks::TaskFile> tasks;
  long steps = 0;        // the problem's simulation time
};

// A LoRR problem JSON (tasks/lorr_problem.hpp); InputError "file:line: what" on bad input.
Problem load_problem(const std::string& path);

struct Evaluation {
  double throughput = 0;  // errands per step
  long planner_errors = 0;
  double cpu_p99_ms = 0;  // planner CPU per step
};

// One run of `steps` steps (<= 0: the problem's) with `seed`.
Evaluation evaluate(const Problem& pr, const planner::Guidance& gd, long steps, uint64_t seed,
                    const planner::Epibt::Options& ep = {});

}  // namespace ggo
