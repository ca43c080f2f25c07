#include "tasks/roundrobin.hpp"

namespace tasks {

void RoundRobin::on_start(const planner::Config& positions)
{
  for (int a = 0; a < num_agents(); ++a) next_task(a, a, positions[a]);
}

void RoundRobin::on_finished(int agent, const Task& task)
{
  next_task(agent, task.id + num_agents(), task.errands.back());  // it stands on its last errand
}

void RoundRobin::next_task(int agent, long id, planner::Vertex at)
{
  Task t = make_task(id);
  // The battery's task check (battery.hpp; the pool does it when it matches): a task whose
  // moves and the way on to a charger the charge does not cover waits until it has charged.
  if (!needs_charge(agent) && !affords(agent, task_moves(at, t), t)) charge_instead(agent, at);
  if (needs_charge(agent)) {
    deferred_.resize(num_agents(), -1);
    deferred_[agent] = id;
    return;
  }
  give(agent, add_task(std::move(t)));
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
