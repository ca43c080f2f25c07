#include "tasks/lifelong_epochs.hpp"

#include <algorithm>
#include <utility>

#include "planner/budget.hpp"
#include "planner/rotation/rotation_planner.hpp"
#include "tasks/lifelong_goal.hpp"
#include "tasks/urgency.hpp"

namespace tasks {

void start_epoch(const TaskManager& tasks, planner::RealtimePlanner& p, const planner::Config& goals)
{
  hint_priorities(tasks, p);  // stalled errands, low batteries: only at an epoch start
  p.set_goals(goals, lifelong_goal_test(tasks, p.current()));
}

void LifelongEpochs::start(const planner::Graph& g, const planner::Config& starts, std::unique_ptr<FreeFlowBound> bound,
                           std::shared_ptr<planner::DistCache> cache)
{
  if (!tasks_.stalls()) tasks_.watch_stalls(g);  // before share_dist_cache: its tables then come from the cache
  if (cache) tasks_.share_dist_cache(std::move(cache));
  tasks_.set_free_flow(std::move(bound));
  tasks_.start(starts);
  r_.epochs = 1;
  is_station_.assign(g.size(), 0);
  heading_count_.assign(g.size(), 0);
  for (const std::vector<planner::Vertex>& task : tasks_.file().tasks)
    for (planner::Vertex v : task) is_station_[v] = 1;
}

bool LifelongEpochs::complete(long t, const planner::Config& real)
{
  const auto t0 = planner::Clock::now();
  ev_ = tasks_.update(t, real);
  r_.task_ms += planner::ms_since(t0);
  if (!ev_.empty()) last_completion_ = t;
  max_gap_ = std::max(max_gap_, t - last_completion_);
  return !ev_.empty() || tasks_.goals_changed();  // goals change without a completion only with station queues
}

void LifelongEpochs::prefetch(planner::DistCache& cache, const planner::Config& at) const
{
  std::vector<std::pair<int32_t, planner::DistCache::Want>> order;
  for (const auto& u : tasks_.upcoming()) {
    const planner::Vertex now = tasks_.goals()[u.agent];
    order.push_back({cache.table(now)->at(at[u.agent], cache.graph()), {u.goal, now}});
  }
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<planner::DistCache::Want> wants;
  wants.reserve(order.size());
  for (const auto& o : order) wants.push_back(o.second);
  cache.prefetch(wants);
}

void LifelongEpochs::prefetch(planner::RotationPlanner& rot) const
{
  std::vector<std::pair<uint16_t, planner::Vertex>> order;
  for (const auto& u : tasks_.upcoming()) order.push_back({rot.h(u.agent), u.goal});
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<planner::Vertex> goals;
  goals.reserve(order.size());
  for (const auto& o : order) goals.push_back(o.second);
  rot.prefetch(goals);
}

void LifelongEpochs::record(bool epoch)
{
  record_epoch(epoch);
  record_events(ev_);
}

void LifelongEpochs::count(long t, const planner::Config& real)
{
  const planner::Config& goals = tasks_.goals();
  if (goal_.size() != goals.size()) goal_ = goals, goal_start_.assign(goals.size(), 0);
  for (size_t i = 0; i < goals.size(); ++i) {
    if (goals[i] != goal_[i]) goal_[i] = goals[i], goal_start_[i] = t;
    counts_.max_goal_ticks = std::max(counts_.max_goal_ticks, t - goal_start_[i]);
  }
  // A counter per cell, reset after use: no allocation per step (1000 agents, 5000 steps).
  counts_.idle = counts_.parked = 0;
  counts_.clearings = tasks_.queues() ? tasks_.queues()->clearings() : 0;
  counts_.jam_clearings = tasks_.queues() ? tasks_.queues()->jam_clearings() : 0;
  counts_.clearing_steps = tasks_.queues() ? tasks_.queues()->clearing_steps() : 0;
  counts_.longest_clearing = tasks_.queues() ? tasks_.queues()->longest_clearing() : 0;
  for (int a = 0; a < tasks_.num_agents(); ++a) {
    if (tasks_.heading(a) && is_station_[goals[a]])
      counts_.max_heading = std::max(counts_.max_heading, ++heading_count_[goals[a]]);
    if (tasks_.busy(a) && !tasks_.heading(a) && real[a] == goals[a]) ++counts_.queued_ticks;
    if (!tasks_.busy(a)) {
      ++counts_.idle;
      counts_.parked += tasks_.parking() && tasks_.parking()->is_parking(real[a]);
    }
  }
  for (int a = 0; a < tasks_.num_agents(); ++a) heading_count_[goals[a]] = 0;
  counts_.idle_ticks += counts_.idle, counts_.parked_ticks += counts_.parked;
}

}  // namespace tasks
