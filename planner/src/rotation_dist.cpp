#include "planner/rotation_dist.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace planner {

namespace {
constexpr int kDx[4] = {1, 0, -1, 0};
constexpr int kDy[4] = {0, 1, 0, -1};
}  // namespace

RotationDist::RotationDist(const Graph& g, size_t max_tables) : g_(g), max_tables_(max_tables)
{
  if (!g.is_grid()) throw std::invalid_argument("rotation distances need a grid graph");
  ahead_.assign(static_cast<size_t>(g.size()) * 4, -1);
  for (Vertex v = 0; v < g.size(); ++v)
    for (int o = 0; o < 4; ++o) ahead_[static_cast<size_t>(v) * 4 + o] = g.at(g.cell_x(v) + kDx[o], g.cell_y(v) + kDy[o]);
}

RotationDist::Table* RotationDist::table(Vertex goal)
{
  auto it = tables_.find(goal);
  if (it != tables_.end()) return it->second.get();
  auto t = std::make_unique<Table>();
  t->goal = goal;
  t->dist.assign(static_cast<size_t>(g_.size()) * 4, kInf);
  for (int o = 0; o < 4; ++o) {
    t->dist[static_cast<size_t>(goal) * 4 + o] = 0;
    t->queue.push_back(goal * 4 + o);
  }
  t->used = ++tick_;
  Table* out = t.get();
  tables_.emplace(goal, std::move(t));
  return out;
}

uint16_t RotationDist::grow_until(Table* t, int32_t state) const
{
  grow(t, state, SIZE_MAX);
  return t->dist[static_cast<size_t>(state)];
}

void RotationDist::grow(Table* t, int32_t state, size_t pops) const
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
    const int32_t pred[3] = {v * 4 + (o + 3) % 4, v * 4 + (o + 1) % 4,
                             ahead_[static_cast<size_t>(v) * 4 + (o + 2) % 4] >= 0
                                 ? ahead_[static_cast<size_t>(v) * 4 + (o + 2) % 4] * 4 + o
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
  for (const auto& kv : tables_) b += kv.second->dist.capacity() * sizeof(uint16_t) + kv.second->queue.capacity() * sizeof(int32_t);
  return b;
}

}  // namespace planner
