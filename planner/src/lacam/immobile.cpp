#include "planner/lacam/immobile.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <queue>
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

DetourTable::DetourTable(const Graph& g, DistTable* plain)
    : g_(g), own_(plain ? nullptr : std::make_unique<DistTable>(g)), plain_(plain ? plain : own_.get())
{
}

DetourTable::~DetourTable() = default;

void DetourTable::set_blocked(std::vector<Vertex> blocked)
{
  std::sort(blocked.begin(), blocked.end());
  if (blocked == blocked_) return;
  blocked_ = std::move(blocked);
  for (const Shadow& s : shadows_) shadow_of_[s.goal] = -1;
  shadows_.clear();
  to_blocked_.assign(blocked_.size(), {});
  for (size_t k = 0; k < blocked_.size(); ++k) {
    std::vector<int32_t>& d = to_blocked_[k];
    d.assign(g_.size(), DistTable::kInf);
    d[blocked_[k]] = 0;
    if (!g_.weighted()) {
      std::vector<Vertex> q{blocked_[k]};
      for (size_t h = 0; h < q.size(); ++h)
        for (Vertex u : g_.in_neighbors(q[h]))
          if (d[u] == DistTable::kInf) d[u] = d[q[h]] + 1, q.push_back(u);
      continue;
    }
    // Move costs (graph.hpp): a move u -> w costs w's cost; Dijkstra.
    using Item = std::pair<int32_t, Vertex>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    open.push({0, blocked_[k]});
    while (!open.empty()) {
      const auto [dw, w] = open.top();
      open.pop();
      if (dw > d[w]) continue;
      for (Vertex u : g_.in_neighbors(w))
        if (dw + g_.move_cost(w) < d[u]) d[u] = dw + g_.move_cost(w), open.push({d[u], u});
    }
  }
}

bool DetourTable::blocked(Vertex v) const { return std::binary_search(blocked_.begin(), blocked_.end(), v); }

int32_t DetourTable::get(Vertex goal, Vertex v) { return get(goal, v, plain_->cache()->table(goal)); }

int32_t DetourTable::get(Vertex goal, Vertex v, DistCache::Table* t)
{
  if (blocked(v) || blocked(goal)) return DistTable::kInf;
  const int32_t dv = t->at(v, g_);
  // The blocked vertices d's BFS has found (all those nearer the goal than v among them).
  size_t found = 0;
  bool through = false;  // some shortest path from v runs through a blocked vertex
  for (size_t k = 0; k < blocked_.size(); ++k) {
    const int32_t db = t->dist[blocked_[k]];
    if (db == DistTable::kInf) continue;
    ++found;
    through = through || (to_blocked_[k][v] != DistTable::kInf && db + to_blocked_[k][v] == dv);
  }
  if (shadow_of_.empty()) shadow_of_.assign(g_.size(), -1);
  int32_t k = shadow_of_[goal];
  if (k < 0 || shadows_[k].found != found) {
    if (!through) return dv;  // not in any shadow: no need to search it yet
    // Past the step's deadline (the plain tables' own, dist_cache.hpp) no shadow is searched:
    // d is a lower bound, and a later step's query searches it.
    const DistCache& c = *plain_->cache();
    if (c.bounded() && std::chrono::steady_clock::now() >= c.deadline()) return dv;
    if (k < 0) {
      k = shadow_of_[goal] = static_cast<int32_t>(shadows_.size());
      shadows_.emplace_back();
      shadows_.back().goal = goal;
    }
    build(shadows_[k], found, t);
  }
  const Shadow& s = shadows_[k];
  if (s.dist.empty()) return dv;
  const auto at = s.dist.find(v);
  return at == s.dist.end() ? dv : at->second;
}

void DetourTable::build(Shadow& s, size_t found, DistCache::Table* t)
{
  s.found = found;
  s.dist.clear();
  auto d = [&](Vertex u) { return ++searched_, t->at(u, g_); };
  if (stamp_.size() != static_cast<size_t>(g_.size())) stamp_.assign(g_.size(), 0);
  if (++epoch_ == 0) std::fill(stamp_.begin(), stamp_.end(), 0), epoch_ = 1;
  auto out = [&](Vertex u) { return stamp_[u] == epoch_ || blocked(u); };  // shadowed or blocked
  // The shadow in order of d: a candidate is a vertex one step farther than a blocked or
  // shadowed one, with a move onto it. (A move onto w costs c(w) = g_.move_cost(w): 1
  // without move costs.)
  auto c = [&](Vertex w) { return g_.move_cost(w); };
  std::map<int32_t, std::vector<Vertex>> next;  // d -> candidates
  for (Vertex b : blocked_)
    if (t->dist[b] != DistTable::kInf)
      for (Vertex u : g_.in_neighbors(b))
        if (d(u) == t->dist[b] + c(b)) next[d(u)].push_back(u);
  std::vector<Vertex> shadow;
  while (!next.empty()) {
    const auto [du, us] = *next.begin();
    next.erase(next.begin());
    for (Vertex u : us) {
      if (out(u)) continue;
      bool through = true;  // every shortest move from u lands on a blocked / shadowed vertex
      for (Vertex w : g_.neighbors(u))
        if (d(w) == du - c(w) && !out(w)) through = false;
      if (!through) continue;
      s.dist[u] = DistTable::kInf;
      stamp_[u] = epoch_;
      shadow.push_back(u);
      for (Vertex x : g_.in_neighbors(u))
        if (d(x) == du + c(u)) next[du + c(u)].push_back(x);
    }
  }
  // Repaired distances: leave the shadow over a move to a vertex that keeps its d, or
  // through shadowed neighbours (Dijkstra).
  using Item = std::pair<int32_t, Vertex>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  for (Vertex u : shadow) {
    int32_t best = DistTable::kInf;
    for (Vertex w : g_.neighbors(u))
      if (!out(w) && d(w) != DistTable::kInf) best = std::min(best, d(w) + c(w));
    if (best < DistTable::kInf) open.push({best, u});
  }
  while (!open.empty()) {
    const auto [du, u] = open.top();
    open.pop();
    int32_t& cur = s.dist[u];
    if (du >= cur) continue;
    cur = du;
    for (Vertex x : g_.in_neighbors(u)) {
      const auto it = s.dist.find(x);
      if (it != s.dist.end() && du + c(u) < it->second) open.push({du + c(u), x});
    }
  }
}

}  // namespace planner
