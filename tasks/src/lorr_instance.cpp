#include "tasks/lorr_instance.hpp"

#include "planner/error.hpp"
#include "planner/movingai.hpp"

namespace tasks {

LorrInstance load_lorr_instance(const std::string& path, int agents, const std::string& agents_option)
{
  LorrInstance in;
  in.problem = load_lorr_problem(path);
  if (agents > in.problem.team_size)
    throw planner::input_error(path, 0, agents_option + std::to_string(agents) + " but teamSize is " +
                                            std::to_string(in.problem.team_size));
  if (agents > 0) in.problem.team_size = agents;
  in.g = planner::load_map(in.problem.map_file);
  in.starts = load_lorr_agents(in.problem.agent_file, in.g, in.problem.team_size);
  in.tasks = std::make_shared<const TaskFile>(load_lorr_tasks(in.problem.task_file, in.g));
  return in;
}

}  // namespace tasks
