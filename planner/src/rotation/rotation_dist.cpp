#include "planner/rotation/rotation_dist.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <stdexcept>

namespace planner {

RotationDist::RotationDist(const Graph& g, size_t max_tables) : g_(g), max_tables_(max_tables)
{
  if (!g.is_grid()) throw std::invalid_argument("rotation distances need a grid graph");
  // Forward moves follow the graph's arcs (one-way ones included); the backward search
  // walks them in reverse (behind_), so on a directed graph a table is the distance along
  // the arcs, kInf where the goal cannot be reached.
  ahead_.assign(static_cast<size_t>(g.size()) * 4, -1);
  behind_.assign(static_cast<size_t>(g.size()) * 4, -1);
  for (Vertex v = 0; v < g.size(); ++v)
    for (int o = 0; o < 4; ++o) {
      ahead_[static_cast<size_t>(v) * 4 + o] = cell_ahead(g, v, o);
      behind_[static_cast<size_t>(v) * 4 + o] = cell_behind(g, v, o);
    }
  if (g.weighted()) set_guidance(Guidance{});  // the move costs alone
}

void RotationDist::set_guidance(Guidance gd)
{
  if (!gd.forward.empty() && gd.forward.size() != static_cast<size_t>(g_.size()) * 4)
    throw std::invalid_argument("guidance: " + std::to_string(gd.forward.size()) + " forward costs for " +
                                std::to_string(g_.size()) + " cells (4 per cell expected)");
  if (gd.turn < 1 || gd.max_cost() > Guidance::kMaxCost || gd.min_forward() < 1)
    throw std::invalid_argument("guidance: costs must be in 1.." + std::to_string(Guidance::kMaxCost));
  given_ = std::move(gd);
  for (Table* t : late_) t->late = false;
  late_.clear();
  wanted_.clear();
  wanted_head_ = 0;
  tables_.clear();
  guid_ = given_;
  if (costs_on_ && g_.weighted()) {
    // A forward move costs its guidance cost plus the extra time of the cell it enters,
    // (move cost - 1) steps at the cheapest forward cost (a step's price in these units).
    // Added, not multiplied: a guidance penalty against a lane's arrow is a preference, not
    // time, and does not grow with the lane's slowness. (Without guidance both are the move
    // cost; with arrows neither made pibt-rot faster on bench_lane_costs.py: README.)
    const uint32_t step = given_.min_forward();
    guid_.forward.resize(static_cast<size_t>(g_.size()) * 4);
    for (Vertex v = 0; v < g_.size(); ++v)
      for (int o = 0; o < 4; ++o) {
        const size_t s = static_cast<size_t>(v) * 4 + static_cast<size_t>(o);
        const Vertex c = ahead_[s];
        const uint32_t k = uint32_t{given_.forward_cost(v, o)} + (c >= 0 ? static_cast<uint32_t>(g_.move_cost(c)) - 1 : 0) * step;
        guid_.forward[s] = static_cast<uint16_t>(std::min<uint32_t>(k, Guidance::kMaxCost));
      }
  }
  weighted_ = !guid_.uniform();
  min_forward_ = guid_.min_forward();
}

void RotationDist::set_move_costs(bool on)
{
  costs_on_ = on;
  set_guidance(given_);
}

RotationDist::Table* RotationDist::table(Vertex goal)
{
  auto it = tables_.find(goal);
  if (it != tables_.end()) return it->second.get();
  auto t = std::make_unique<Table>();
  t->goal = goal;
  t->dist.assign(static_cast<size_t>(g_.size()) * 4, kInf);
  if (weighted_) t->buckets.resize(static_cast<size_t>(guid_.max_cost()) + 1);
  for (int o = 0; o < 4; ++o) {
    t->dist[static_cast<size_t>(goal) * 4 + o] = 0;
    if (weighted_) t->buckets[0].push_back(goal * 4 + o), ++t->open;
    else t->queue.push_back(goal * 4 + o);
  }
  t->settled = weighted_ ? 0 : kFar;  // BFS: a discovered state's distance is final
  t->used = ++tick_;
  Table* out = t.get();
  tables_.emplace(goal, std::move(t));
  return out;
}

uint16_t RotationDist::grow_until(Table* t, int32_t state) const
{
  const size_t s = static_cast<size_t>(state);
  if (deadline_ == Deadline::max()) {
    grow(t, state, SIZE_MAX);
    return t->dist[s];
  }
  while (!expired_) {
    if (std::chrono::steady_clock::now() >= deadline_) {
      expired_ = true;
      break;
    }
    grow(t, state, 256);
    if (t->dist[s] <= t->settled || t->done()) return t->dist[s];
  }
  if (!t->late) {  // precompute() grows it first; pinned so that trim() keeps it meanwhile
    t->late = true;
    ++t->pins;
    late_.push_back(t);
  }
  ++bounded_answers_;
  return lower_bound(t, state / 4, state % 4);
}

uint16_t RotationDist::lower_bound(const Table* t, Vertex v, int o) const
{
  const size_t s = static_cast<size_t>(v) * 4 + static_cast<size_t>(o);
  if (t->dist[s] <= t->settled || t->done()) return t->dist[s];
  // Every state nearer than the search's open level is settled: (v, o) is beyond it.
  uint32_t lb = t->buckets.empty() ? static_cast<uint32_t>(t->dist[static_cast<size_t>(t->queue[t->head])]) + 1 : t->level + 1;
  // Manhattan distance at the cheapest forward cost, plus the quarter turns to face every
  // direction the robot must move in (one more for the second of two).
  const int dx = g_.cell_x(t->goal) - g_.cell_x(v), dy = g_.cell_y(t->goal) - g_.cell_y(v);
  int need[2], k = 0;
  if (dx != 0) need[k++] = dx > 0 ? 0 : 2;
  if (dy != 0) need[k++] = dy > 0 ? 1 : 3;
  int turns = 0;
  if (k > 0) {
    auto rot = [o](int d) { return quarter_turns(o, d); };
    turns = k == 1 ? rot(need[0]) : std::min(rot(need[0]), rot(need[1])) + 1;
  }
  const uint32_t h = static_cast<uint32_t>(std::abs(dx) + std::abs(dy)) * min_forward_ + static_cast<uint32_t>(turns) * guid_.turn;
  return static_cast<uint16_t>(std::min<uint32_t>(std::max(lb, h), kFar));
}

void RotationDist::grow(Table* t, int32_t state, size_t pops) const
{
  if (t->buckets.empty()) grow_bfs(t, state, pops);
  else grow_dijkstra(t, state, pops);
}

void RotationDist::grow_bfs(Table* t, int32_t state, size_t pops) const
{
  std::vector<int32_t>& q = t->queue;
  std::vector<uint16_t>& dist = t->dist;
  while (t->head < q.size() && pops-- > 0 && (state < 0 || dist[static_cast<size_t>(state)] == kInf)) {
    const int32_t s = q[t->head++];
    const Vertex v = s / 4;
    const int o = s % 4;
    const uint16_t d = dist[static_cast<size_t>(s)];
    const uint16_t nd = d >= kFar - 1 ? kFar : static_cast<uint16_t>(d + 1);
    // Predecessors: turned clockwise from o - 1, counter-clockwise from o + 1, or moved
    // forward (heading o) from the cell behind v.
    const int32_t pred[3] = {v * 4 + turned_ccw(o), v * 4 + turned_cw(o),
                             behind_[static_cast<size_t>(v) * 4 + o] >= 0
                                 ? behind_[static_cast<size_t>(v) * 4 + o] * 4 + o
                                 : -1};
    for (int32_t p : pred)
      if (p >= 0 && dist[static_cast<size_t>(p)] == kInf) {
        dist[static_cast<size_t>(p)] = nd;
        q.push_back(p);
      }
    if (t->head > 4096 && t->head * 2 > q.size()) {  // keep only the open part
      q.erase(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(t->head));
      t->head = 0;
    }
  }
  if (t->done()) {
    std::vector<int32_t>().swap(q);
    t->head = 0;
  }
}

void RotationDist::grow_dijkstra(Table* t, int32_t state, size_t pops) const
{
  std::vector<uint16_t>& dist = t->dist;
  const size_t nb = t->buckets.size();
  while (t->open > 0 && pops > 0) {
    if (state >= 0 && dist[static_cast<size_t>(state)] <= t->level) break;
    std::vector<int32_t>& b = t->buckets[t->level % nb];
    if (b.empty()) {
      ++t->level;
      continue;
    }
    const int32_t s = b.back();
    b.pop_back();
    --t->open;
    if (dist[static_cast<size_t>(s)] != t->level) continue;  // queued again nearer: popped already
    --pops;
    const Vertex v = s / 4;
    const int o = s % 4;
    const Vertex behind = behind_[static_cast<size_t>(v) * 4 + o];
    // Predecessors as in the BFS, each with its action's cost.
    const int32_t pred[3] = {v * 4 + turned_ccw(o), v * 4 + turned_cw(o), behind >= 0 ? behind * 4 + o : -1};
    const uint32_t cost[3] = {guid_.turn, guid_.turn, behind >= 0 ? guid_.forward_cost(behind, o) : 0u};
    for (int k = 0; k < 3; ++k) {
      const int32_t p = pred[k];
      if (p < 0) continue;
      const uint16_t nd = static_cast<uint16_t>(std::min<uint32_t>(t->level + cost[k], kFar));
      if (nd < dist[static_cast<size_t>(p)]) {
        dist[static_cast<size_t>(p)] = nd;
        t->buckets[nd % nb].push_back(p);
        ++t->open;
      }
    }
  }
  t->settled = static_cast<uint16_t>(std::min<uint32_t>(t->level, kFar));
  if (t->open == 0) {  // complete: every distance exact, the buckets are freed
    std::vector<std::vector<int32_t>>().swap(t->buckets);
    t->settled = kFar;
  }
}

void RotationDist::prefetch(const std::vector<Vertex>& goals)
{
  std::vector<Table*> old;
  old.swap(wanted_);
  for (Vertex goal : goals) {  // pin the new queue before unpinning the old: tables in both stay
    Table* t = table(goal);
    pin(t);
    wanted_.push_back(t);
  }
  for (Table* t : old) unpin(t);
  wanted_head_ = 0;
}

bool RotationDist::precompute(std::chrono::steady_clock::time_point deadline)
{
  while (!late_.empty()) {  // tables queries needed this step: first
    Table* t = late_.back();
    if (t->done() || t->pins == 1) {  // complete, or nobody holds it any more (its goal changed): not worth growing
      late_.pop_back();
      t->late = false;
      --t->pins;
      continue;
    }
    if (std::chrono::steady_clock::now() >= deadline) return true;
    grow(t, -1, 256);
  }
  while (wanted_head_ < wanted_.size()) {
    Table* t = wanted_[wanted_head_];
    if (t->done()) {
      ++wanted_head_;
      continue;
    }
    if (std::chrono::steady_clock::now() >= deadline) return true;
    grow(t, -1, 256);
  }
  return false;
}

void RotationDist::trim()
{
  if (max_tables_ == 0 || tables_.size() <= max_tables_) return;
  std::vector<std::pair<uint64_t, Vertex>> idle;
  for (const auto& [goal, t] : tables_)
    if (t->pins == 0) idle.push_back({t->used, goal});
  std::sort(idle.begin(), idle.end());
  for (size_t k = 0; k < idle.size() && tables_.size() > max_tables_; ++k) tables_.erase(idle[k].second);
}

size_t RotationDist::bytes() const
{
  size_t b = 0;
  for (const auto& kv : tables_) {
    b += kv.second->dist.capacity() * sizeof(uint16_t) + kv.second->queue.capacity() * sizeof(int32_t);
    for (const auto& q : kv.second->buckets) b += q.capacity() * sizeof(int32_t);
  }
  return b;
}

}  // namespace planner
