#include "tasks/free_flow.hpp"

namespace tasks {

void FreeFlowBound::errand(int agent, planner::Vertex cell)
{
  const planner::Vertex from = last_[agent];
  last_[agent] = cell;
  ++errands_;
  if (from == cell) return;
  planner::DistCache::Table* t = cache_->table(cell);
  // Exact, whatever the cache's step deadline: this query may take the BFS as far as it needs.
  const int32_t m = t->dist[from] != planner::DistCache::kInf ? t->dist[from] : t->extend_until(from, cache_->graph());
  if (m >= planner::DistCache::kInf) return;
  steps_ += cost_ ? cost_(m) : static_cast<double>(m);
}

}  // namespace tasks
