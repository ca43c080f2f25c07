#include "planner/dist_table.hpp"

namespace planner {

DistTable::Table::Table(const Graph& g, Vertex goal) : dist(g.size(), kInf)
{
  queue.reserve(g.size());
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
  return kInf;  // BFS exhausted: v is unreachable
}

DistTable::DistTable(const Graph& g) : g_(g) {}

DistTable::Table* DistTable::table_for(Vertex goal)
{
  auto it = by_goal_.find(goal);
  if (it != by_goal_.end()) return it->second;
  tables_.push_back(std::make_unique<Table>(g_, goal));
  return by_goal_[goal] = tables_.back().get();
}

void DistTable::set_goals(const Config& goals)
{
  agent_table_.resize(goals.size());
  for (size_t i = 0; i < goals.size(); ++i) agent_table_[i] = table_for(goals[i]);
}

int32_t DistTable::from_goal(Vertex goal, Vertex v)
{
  Table& t = *table_for(goal);
  return t.dist[v] != kInf ? t.dist[v] : t.extend_until(v, g_);
}

}  // namespace planner
