#include "tasks/reachability.hpp"

namespace tasks {

bool Reachability::reaches(planner::Vertex from, planner::Vertex to) const
{
  auto it = to_.find(to);
  if (it == to_.end()) {
    std::vector<uint8_t> seen(g_.size(), 0);
    std::vector<planner::Vertex> open{to};
    seen[to] = 1;
    for (size_t i = 0; i < open.size(); ++i)
      for (planner::Vertex u : g_.in_neighbors(open[i]))
        if (!seen[u]) seen[u] = 1, open.push_back(u);
    it = to_.emplace(to, std::move(seen)).first;
  }
  return it->second[from] != 0;
}

}  // namespace tasks
