#include "planner/dist_table.hpp"

#include <algorithm>

namespace planner {

DistTable::Table::Table(const Graph& g, Vertex goal_vertex) : dist(g.size(), kInf), goal(goal_vertex)
{
  dist[goal] = 0;
  queue.push_back(goal);
}

int32_t DistTable::Table::extend_until(Vertex v, const Graph& g)
{
  // Vertices get their distance when discovered, so stop as soon as v is discovered.
  while (head < queue.size()) {
    Vertex u = queue[head++];
    for (Vertex w : g.neighbors(u)) {
      if (dist[w] != kInf) continue;
      dist[w] = dist[u] + 1;
      queue.push_back(w);
    }
    if (dist[v] != kInf) return dist[v];
  }
  if (!queue.empty()) std::vector<Vertex>().swap(queue), head = 0;  // BFS done: free the queue
  return kInf;  // v is unreachable
}

DistTable::DistTable(const Graph& g, size_t max_tables) : g_(g), max_tables_(max_tables) {}

DistTable::Table* DistTable::table_for(Vertex goal)
{
  auto it = by_goal_.find(goal);
  if (it != by_goal_.end()) return it->second;
  tables_.push_back(std::make_unique<Table>(g_, goal));
  return by_goal_[goal] = tables_.back().get();
}

void DistTable::set_goals(const Config& goals)
{
  ++assign_round_;
  agent_table_.resize(goals.size());
  for (size_t i = 0; i < goals.size(); ++i) {
    agent_table_[i] = table_for(goals[i]);
    agent_table_[i]->last_assigned = assign_round_;
  }
  if (max_tables_ > 0 && tables_.size() > max_tables_) evict();
}

void DistTable::evict()
{
  // Tables assigned in this round are in use; drop the oldest of the others.
  std::sort(tables_.begin(), tables_.end(),
            [](const std::unique_ptr<Table>& a, const std::unique_ptr<Table>& b) { return a->last_assigned > b->last_assigned; });
  size_t keep = max_tables_;
  while (keep < tables_.size() && tables_[keep]->last_assigned == assign_round_) ++keep;
  for (size_t k = keep; k < tables_.size(); ++k) by_goal_.erase(tables_[k]->goal);
  tables_.resize(keep);
}

int32_t DistTable::from_goal(Vertex goal, Vertex v)
{
  Table& t = *table_for(goal);
  return t.dist[v] != kInf ? t.dist[v] : t.extend_until(v, g_);
}

}  // namespace planner
