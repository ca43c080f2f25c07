#include "tasks/free_flow.hpp"

namespace tasks {

void FreeFlowBound::errand(int agent, planner::Vertex cell)
{
  const planner::Vertex from = last_[agent];
  last_[agent] = cell;
  ++errands_;
  steps_ += price(from, cell);
}

double FreeFlowBound::open_steps(const planner::Config& open) const
{
  double steps = 0;
  for (size_t a = 0; a < open.size() && a < last_.size(); ++a)
    if (open[a] >= 0) steps += price(last_[a], open[a]);
  return steps;
}

std::pair<long, double> FreeFlowBound::totals(const planner::Config& open) const
{
  long n = errands_;
  for (planner::Vertex v : open) n += v >= 0;
  return {n, steps_ + open_steps(open)};
}

double FreeFlowBound::price(planner::Vertex from, planner::Vertex to) const
{
  if (from == to) return 0;
  planner::DistCache::Table* t = cache_->table(to);
  // Exact, whatever the cache's step deadline: this query may take the BFS as far as it needs.
  const int32_t m = t->dist[from] != planner::DistCache::kInf ? t->dist[from] : t->extend_until(from, cache_->graph());
  if (m >= planner::DistCache::kInf) return 0;
  return cost_ ? cost_(m) : static_cast<double>(m);
}

}  // namespace tasks
