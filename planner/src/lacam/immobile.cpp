#include "planner/lacam/immobile.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "planner/dist_table.hpp"

namespace planner {

bool any_immobile(const std::vector<uint8_t>& immobile)
{
  return std::find(immobile.begin(), immobile.end(), 1) != immobile.end();
}

void check_immobile_agent(int agent, size_t n)
{
  if (agent < 0 || static_cast<size_t>(agent) >= n)
    throw std::invalid_argument("set_immobile: agent " + std::to_string(agent) + " out of range (0.." +
                                std::to_string(static_cast<long long>(n) - 1) + ")");
}

GoalTest relaxed_goal_test(const Graph& g, const Config& current, const Config& goals,
                           const std::vector<uint8_t>& immobile, GoalTest test)
{
  if (test || !any_immobile(immobile)) return test;
  const int n = static_cast<int>(current.size());
  // Strong components of the graph without the immobile agents' vertices: an agent must
  // reach its goal only if it can get there and back (on an undirected graph: the
  // connected components).
  std::vector<uint8_t> blocked(g.size(), 0);
  for (int i = 0; i < n; ++i)
    if (immobile[i]) blocked[current[i]] = 1;
  const std::vector<int> comp = g.strong_components(nullptr, &blocked);
  std::vector<int32_t> need;  // agents that must be on their goals
  for (int i = 0; i < n; ++i)
    if (!immobile[i] && comp[goals[i]] >= 0 && comp[goals[i]] == comp[current[i]]) need.push_back(i);
  return [need, goals](const Vertex* C) {
    for (int32_t i : need)
      if (C[i] != goals[i]) return false;
    return true;
  };
}

void DetourTable::set_blocked(std::vector<Vertex> blocked)
{
  std::sort(blocked.begin(), blocked.end());
  if (blocked == blocked_) return;
  blocked_ = std::move(blocked);
  tables_.clear();
}

int32_t DetourTable::get(Vertex goal, Vertex v)
{
  auto it = tables_.find(goal);
  if (it == tables_.end()) {
    std::vector<int32_t> d(g_.size(), DistTable::kInf);
    std::vector<Vertex> queue;
    auto blocked = [&](Vertex u) { return std::binary_search(blocked_.begin(), blocked_.end(), u); };
    if (!blocked(goal)) {
      d[goal] = 0;
      queue.push_back(goal);
    }
    for (size_t k = 0; k < queue.size(); ++k)
      for (Vertex u : g_.in_neighbors(queue[k]))  // distances *to* goal: arcs backwards
        if (d[u] == DistTable::kInf && !blocked(u)) d[u] = d[queue[k]] + 1, queue.push_back(u);
    it = tables_.emplace(goal, std::move(d)).first;
  }
  return it->second[v];
}

}  // namespace planner
