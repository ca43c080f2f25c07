#include "planner/rotation/st_astar_rot.hpp"

#include <algorithm>
#include <cstdint>

namespace planner {

void RotReservations::reset(int cells, int window)
{
  cells_ = static_cast<size_t>(cells);
  window_ = window;
  occ_.assign(cells_ * static_cast<size_t>(window + 1), -1);
}

void RotReservations::add(int agent, const RotPath& p)
{
  for (int t = 0; t <= window_; ++t) occ_[static_cast<size_t>(t) * cells_ + static_cast<size_t>(p[t].v)] = agent;
}

void RotReservations::remove(int agent, const RotPath& p)
{
  for (int t = 0; t <= window_; ++t) {
    int32_t& o = occ_[static_cast<size_t>(t) * cells_ + static_cast<size_t>(p[t].v)];
    if (o == agent) o = -1;
  }
}

int64_t windowed_cost(const RotationDist& dist, RotationDist::Table* t, Vertex goal, const RotPath& p)
{
  const int w = static_cast<int>(p.size()) - 1;
  for (int k = 0; k <= w; ++k)
    if (p[k].v == goal) return k;
  return w + static_cast<int64_t>(dist.get(t, p[w].v, p[w].o));
}

int64_t StAstarRot::plan(RotState s, Vertex goal, RotationDist::Table* table, const RotReservations& res, RotPath& out,
                         std::chrono::steady_clock::time_point deadline)
{
  const int w = res.window();
  const int32_t cells = dist_.graph().size();
  const size_t keys = static_cast<size_t>(w + 1) * static_cast<size_t>(cells) * 8;
  if (node_.size() < keys) node_.resize(keys);
  if (++stamp_ == 0) {  // wrapped: forget every old stamp
    for (Node& x : node_) x.seen = x.closed = 0;
    stamp_ = 1;
  }
  auto key = [cells](int t, Vertex v, int o, int r) { return ((t * cells + v) * 4 + o) * 2 + r; };
  auto h = [&](Vertex v, int o, int r) -> int64_t { return r ? 0 : dist_.get(table, v, o); };
  // Open list: one LIFO bucket per f (f values are small integers); `lo` is at or below the
  // least nonempty bucket (h may be inconsistent: guided or bounded, so f can drop).
  size_t lo = SIZE_MAX, hi = 0, open = 0;
  auto push = [&](int t, Vertex v, int o, int r, int32_t g, int32_t from) {
    const int32_t k = key(t, v, o, r);
    Node& x = node_[static_cast<size_t>(k)];
    if (x.closed == stamp_ || (x.seen == stamp_ && x.g <= g)) return;
    x.seen = stamp_;
    x.g = g;
    x.parent = from;
    const size_t f = static_cast<size_t>(g + h(v, o, r));
    if (f >= bucket_.size()) bucket_.resize(f + 1);
    bucket_[f].push_back(k);
    lo = std::min(lo, f), hi = std::max(hi, f), ++open;
  };
  auto clear = [&] {
    for (size_t f = lo; open > 0 && f <= hi; ++f) open -= bucket_[f].size(), bucket_[f].clear();
  };
  push(0, s.v, s.o, s.v == goal ? 1 : 0, 0, -1);
  uint64_t n = 0;
  while (open > 0) {
    while (bucket_[lo].empty()) ++lo;
    const int32_t k = bucket_[lo].back();
    bucket_[lo].pop_back();
    --open;
    Node& x = node_[static_cast<size_t>(k)];
    if (x.closed == stamp_) continue;
    x.closed = stamp_;
    ++expanded_;
    if ((++n & 1023) == 0 && std::chrono::steady_clock::now() >= deadline) {
      clear();
      return -1;
    }
    const int r = k & 1, o = (k >> 1) & 3;
    const Vertex v = (k >> 3) % cells;
    const int t = (k >> 3) / cells;
    if (t == w) {  // the window's end: its f is the windowed cost
      const int64_t f = static_cast<int64_t>(lo);
      out.assign(static_cast<size_t>(w) + 1, RotState{});
      for (int32_t c = k; c >= 0; c = node_[static_cast<size_t>(c)].parent)
        out[static_cast<size_t>((c >> 3) / cells)] = {(c >> 3) % cells, (c >> 1) & 3};
      clear();
      return f;
    }
    const int32_t step = r ? 0 : 1;  // after the goal, staying in the window costs nothing
    const int32_t g = x.g + step;
    if (res.vertex_free(v, t + 1)) {
      push(t + 1, v, o, r, g, k);            // W
      push(t + 1, v, (o + 1) & 3, r, g, k);  // R
      push(t + 1, v, (o + 3) & 3, r, g, k);  // C
    }
    const Vertex u = dist_.ahead(v, o);
    if (u >= 0 && res.move_free(v, u, t)) push(t + 1, u, o, r || u == goal, g, k);  // F
  }
  return -1;
}

}  // namespace planner
