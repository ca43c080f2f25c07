#include "tasks/roundrobin.hpp"

namespace tasks {

void RoundRobin::on_start(const planner::Config&)
{
  for (int a = 0; a < num_agents(); ++a) give(a, add_task(make_task(a)));
}

void RoundRobin::on_finished(int agent, const Task& task)
{
  if (needs_charge(agent)) {
    deferred_.resize(num_agents(), -1);
    deferred_[agent] = task.id + num_agents();
    return;
  }
  give(agent, add_task(make_task(task.id + num_agents())));
}

void RoundRobin::on_dropped(int agent, int s)
{
  dropped_.resize(num_agents(), -1);
  dropped_[agent] = s;
}

void RoundRobin::on_charged(int agent)
{
  if (agent < static_cast<int>(dropped_.size()) && dropped_[agent] >= 0) {
    give(agent, dropped_[agent]);
    dropped_[agent] = -1;
    return;
  }
  if (agent >= static_cast<int>(deferred_.size()) || deferred_[agent] < 0) return;
  give(agent, add_task(make_task(deferred_[agent])));
  deferred_[agent] = -1;
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
