#include "tasks/errand_stalls.hpp"

#include <algorithm>

namespace tasks {

void ErrandStalls::completed(long t, long task, int errand)
{
  const auto it = open_.find(task);
  if (it == open_.end() || it->second.errand != errand) return;  // opened and completed in one step
  const Open& o = it->second;
  open_ticks_.push_back(t - o.opened);
  stall_ticks_.push_back(std::max(o.max_gap, static_cast<long long>(t - o.mark)));
  open_.erase(it);
}

void ErrandStalls::observe(long t, const std::vector<Held>& held, const planner::Config& positions)
{
  // Each agent's goal for the tables: its errand cell, or where it stands (a table it
  // never reads, usually one the planner holds anyway).
  if (goals_.empty() && !shared_) dist_.set_max_tables(2 * positions.size() + 64);  // a cache of its own: bounded
  goals_.resize(positions.size());
  for (size_t a = 0; a < positions.size(); ++a) goals_[a] = held[a].task >= 0 ? held[a].cell : positions[a];
  dist_.set_goals(goals_);
  for (size_t a = 0; a < positions.size(); ++a) {
    const Held& h = held[a];
    if (h.task < 0) continue;
    planner::DistCache::Table* tab = dist_.table(static_cast<int>(a));
    const planner::Vertex v = positions[a];
    const int32_t d = tab->dist[v] != planner::DistCache::kInf ? tab->dist[v] : tab->extend_until(v, g_);  // exact, whatever the deadline
    auto [it, fresh] = open_.try_emplace(h.task);
    Open& o = it->second;
    if (fresh || o.errand != h.errand) {
      o = Open{h.errand, t, t, d, static_cast<int>(a), 0};
    } else if (o.holder != static_cast<int>(a)) {
      o.holder = static_cast<int>(a), o.best = d;  // a new holder: no mark
    } else if (d < o.best) {
      o.max_gap = std::max(o.max_gap, static_cast<long long>(t - o.mark));
      o.mark = t, o.best = d;
    }
  }
}

long long ErrandStalls::stalled(long t, long task) const
{
  const auto it = open_.find(task);
  if (it == open_.end()) return 0;
  const long long now = t - it->second.mark;
  return sticky_ ? std::max(now, it->second.max_gap) : now;
}

long long ErrandStalls::longest(long t, long task) const
{
  const auto it = open_.find(task);
  return it == open_.end() ? 0 : std::max(static_cast<long long>(t - it->second.mark), it->second.max_gap);
}

long ErrandStalls::last_mark(long task) const
{
  const auto it = open_.find(task);
  return it == open_.end() ? -1 : it->second.mark;
}

int32_t ErrandStalls::distance(planner::Vertex cell, planner::Vertex v) const
{
  planner::DistCache::Table* tab = dist_.cache()->table(cell);
  return tab->dist[v] != planner::DistCache::kInf ? tab->dist[v] : tab->extend_until(v, g_);
}

int32_t ErrandStalls::best(long task) const
{
  const auto it = open_.find(task);
  return it == open_.end() ? -1 : it->second.best;
}

ErrandStalls::Summary ErrandStalls::summary(long t) const
{
  std::vector<long long> open = open_ticks_, stall = stall_ticks_;
  for (const auto& [task, o] : open_) {
    open.push_back(t - o.opened);
    stall.push_back(std::max(o.max_gap, static_cast<long long>(t - o.mark)));
  }
  Summary s;
  s.errands = static_cast<long long>(open.size());
  if (open.empty()) return s;
  auto p99 = [](std::vector<long long>& v) {  // nearest rank
    const size_t k = (99 * v.size() + 99) / 100 - 1;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
    return v[k];
  };
  s.max_open = *std::max_element(open.begin(), open.end());
  s.max_stall = *std::max_element(stall.begin(), stall.end());
  s.p99_open = p99(open);
  s.p99_stall = p99(stall);
  return s;
}

}  // namespace tasks
