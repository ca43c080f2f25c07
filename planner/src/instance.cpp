#include "planner/instance.hpp"

#include <queue>
#include <unordered_map>

#include "planner/error.hpp"

namespace planner {
namespace {

// Distances to `s` (BFS backwards along arcs: in-neighbours).
std::vector<int> bfs_to(const Graph& g, Vertex s)
{
  std::vector<int> d(g.size(), -1);
  std::queue<Vertex> q;
  d[s] = 0;
  q.push(s);
  while (!q.empty()) {
    Vertex v = q.front();
    q.pop();
    for (Vertex u : g.in_neighbors(v))
      if (d[u] < 0) d[u] = d[v] + 1, q.push(u);
  }
  return d;
}

}  // namespace

void Instance::check(const Graph& g, bool distinct_goals) const
{
  const std::string file = source.empty() ? std::string("instance") : source;
  auto fail = [&](int i, const std::string& what) {
    int line = i < static_cast<int>(source_lines.size()) ? source_lines[i] : 0;
    throw input_error(file, line, "agent " + std::to_string(i) + ": " + what);
  };

  if (starts.size() != goals.size())
    throw input_error(file, 0, std::to_string(starts.size()) + " starts but " + std::to_string(goals.size()) + " goals");
  std::unordered_map<Vertex, int> start_of, goal_of;
  for (int i = 0; i < num_agents(); ++i) {
    if (starts[i] < 0 || starts[i] >= g.size()) fail(i, "start is not a vertex of the graph");
    if (goals[i] < 0 || goals[i] >= g.size()) fail(i, "goal is not a vertex of the graph");
    if (auto [it, fresh] = start_of.emplace(starts[i], i); !fresh)
      fail(i, "duplicate start (same vertex as agent " + std::to_string(it->second) + ")");
    if (distinct_goals)
      if (auto [it, fresh] = goal_of.emplace(goals[i], i); !fresh)
        fail(i, "duplicate goal (same vertex as agent " + std::to_string(it->second) + ")");
  }
  if (!g.directed()) {
    auto comp = g.components();
    for (int i = 0; i < num_agents(); ++i)
      if (comp[starts[i]] != comp[goals[i]]) fail(i, "goal unreachable from start");
    return;
  }
  // One-way arcs: reachability is not symmetric, so search from each distinct goal backwards.
  std::unordered_map<Vertex, std::vector<int>> to_goal;
  for (int i = 0; i < num_agents(); ++i) {
    auto it = to_goal.find(goals[i]);
    if (it == to_goal.end()) it = to_goal.emplace(goals[i], bfs_to(g, goals[i])).first;
    if (it->second[starts[i]] < 0)
      fail(i, "goal " + std::to_string(goals[i]) + " unreachable from start " + std::to_string(starts[i]) +
                  " along the one-way arcs");
  }
}

long long Instance::soc_lower_bound(const Graph& g) const
{
  // One BFS per distinct goal.
  std::unordered_map<Vertex, std::vector<int>> dist;
  long long sum = 0;
  for (int i = 0; i < num_agents(); ++i) {
    auto it = dist.find(goals[i]);
    if (it == dist.end()) it = dist.emplace(goals[i], bfs_to(g, goals[i])).first;
    sum += it->second[starts[i]];
  }
  return sum;
}

}  // namespace planner
