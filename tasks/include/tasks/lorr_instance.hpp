#pragma once
// LorrInstance: a LoRR problem JSON with everything it names loaded: the map as a graph, the
// team's starts and the task file. The one loader rtlacam-lifelong, the Python module and
// rtlacam-ggo share.
#include <memory>
#include <string>

#include "planner/config.hpp"
#include "planner/graph.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/lorr_problem.hpp"

namespace tasks {

struct LorrInstance {
  LorrProblem problem;  // problem.team_size = the agents loaded
  planner::Graph g;
  planner::Config starts;
  std::shared_ptr<const TaskFile> tasks;
};

// agents > 0: only the first `agents` of the team; more than teamSize is an InputError
// "path: <agents_option><agents> but teamSize is T" (agents_option names the caller's option,
// "--agents " or "agents="). Bad files: InputError naming file:line (the readers').
LorrInstance load_lorr_instance(const std::string& path, int agents = 0, const std::string& agents_option = "--agents ");

}  // namespace tasks
