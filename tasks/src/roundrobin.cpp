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

std::vector<TaskManager::Upcoming> RoundRobin::upcoming() const
{
  std::vector<Upcoming> out = TaskManager::upcoming();
  for (int a = 0; a < num_agents(); ++a)
    if (const Task* k = task_of(a); k && k->next + 1 >= static_cast<int>(k->errands.size()))
      out.push_back({a, file_->tasks[(k->id + num_agents()) % file_->size()][0]});
  return out;
}

}  // namespace tasks
