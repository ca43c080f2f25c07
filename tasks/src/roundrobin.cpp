#include "tasks/roundrobin.hpp"

namespace tasks {

void RoundRobin::on_start(const planner::Config&)
{
  for (int a = 0; a < num_agents(); ++a) give(a, add_task(make_task(a)));
}

void RoundRobin::on_finished(int agent, const Task& task)
{
  give(agent, add_task(make_task(task.id + num_agents())));
}

}  // namespace tasks
