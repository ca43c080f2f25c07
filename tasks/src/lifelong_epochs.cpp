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
  if (epoch) ++r_.epochs;
  r_.events.insert(r_.events.end(), ev_.begin(), ev_.end());
}

}  // namespace tasks
