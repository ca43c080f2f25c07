#include "planner/lacam/local_guidance.hpp"

#include <algorithm>
#include <functional>

namespace planner {

bool LocalGuidance::prepare()
{
  const size_t V = static_cast<size_t>(g_.size());
  if (tw_ == w_ && V_ == V) return false;
  tw_ = w_, V_ = V;  // (re)size: everything unmarked
  cnt_.assign(V_ * (w_ + 1), 0);
  who_.assign(V_ * (w_ + 1), -1);
  closed_.assign(V_ * (w_ + 1), 0);
  call_ = 0;
  from_copy_.clear();
  planned_list_.clear();
  marked_.clear();
  paths_.clear();
  return true;
}

void LocalGuidance::begin(const Vertex* from, int n, const Vertex* goals)
{
  const size_t len = static_cast<size_t>(n) * (w_ + 1);
  round_nodes_ = 0;
  prepare();
  if (refresh_ > 0 && paths_.size() == len && marked_.size() == static_cast<size_t>(n) &&
      std::equal(goals, goals + n, goals_copy_.begin(), goals_copy_.end())) {
    keep(from, n);
    return;
  }
  // Unmark the last round: its planned paths (t >= 1) and its start (t = 0).
  for (int32_t j : planned_list_)
    for (int t = 1; t <= w_; ++t) {
      const Vertex v = paths_[static_cast<size_t>(j) * (w_ + 1) + t];
      cnt_[at(t, v)] = 0;
      who_[at(t, v)] = -1;
    }
  planned_list_.clear();
  for (size_t j = 0; j < marked_.size(); ++j)
    if (marked_[j]) unmark(static_cast<int32_t>(j));
  for (Vertex v : from_copy_) who_[at(0, v)] = -1;
  n_ = n;
  from_ = from;
  goals_ = goals;
  from_copy_.assign(from, from + n);
  if (refresh_ > 0) goals_copy_.assign(goals, goals + n), marked_.assign(n, 0), age_.assign(n, 0);
  for (int i = 0; i < n; ++i) who_[at(0, from[i])] = i;
  if (paths_.size() != len) paths_.assign(len, -1);
  if (stamp_of_.size() != static_cast<size_t>(n)) stamp_of_.assign(n, 0), round_ = 0;
  if (++round_ == 0) std::fill(stamp_of_.begin(), stamp_of_.end(), 0), round_ = 1;
}

// Amortized round: the last round's paths, shifted by the step the configuration advanced,
// stay where they still start at the agent's vertex (header). They leave the tables: Pibt puts
// each back (hold) at its turn in priority order, so that an agent planned again meets only
// the paths of the agents before it, as in LG-LaCAM (with every kept path in the tables, a
// high-priority agent would yield to low-priority ones and the descent wandered: SOC x20 on
// random-32-32-20 N = 300).
void LocalGuidance::keep(const Vertex* from, int n)
{
  const int shift = std::equal(from, from + n, from_copy_.begin()) ? 0 : 1;
  for (int j = 0; j < n; ++j)
    if (marked_[j]) unmark(j);
  for (Vertex v : from_copy_) who_[at(0, v)] = -1;
  from_copy_.assign(from, from + n);
  for (int i = 0; i < n; ++i) who_[at(0, from[i])] = i;
  from_ = from;
  const uint32_t last = round_;
  if (++round_ == 0) std::fill(stamp_of_.begin(), stamp_of_.end(), 0), round_ = 1;
  for (int j = 0; j < n; ++j) {
    Vertex* p = paths_.data() + static_cast<size_t>(j) * (w_ + 1);
    if (stamp_of_[j] != last || p[shift] != from[j]) continue;  // none, or not followed
    if (shift == 1) {  // one step on, and one greedy step at the window's end
      std::copy(p + 1, p + w_ + 1, p);
      const Vertex end = p[w_ - 1];
      Vertex best = end;
      for (Vertex u : g_.neighbors(end))
        if (end != goals_[j] && d_.get(j, u) < d_.get(j, best)) best = u;
      p[w_] = best;
    }
    if (age_[j] < UINT16_MAX) ++age_[j];
    stamp_of_[j] = round_;
    ++kept_total_;
  }
}

void LocalGuidance::mark(int32_t i)
{
  const Vertex* p = path(i);
  for (int t = 1; t <= w_; ++t) {
    uint16_t& c = cnt_[at(t, p[t])];
    if (c < UINT16_MAX) ++c;
    who_[at(t, p[t])] = i;
  }
  if (refresh_ > 0) marked_[i] = 1;
  else planned_list_.push_back(i);
}

bool LocalGuidance::blocked(int32_t i) const
{
  const Vertex* p = path(i);
  for (int t = 1; t <= w_; ++t) {
    if (cnt_[at(t, p[t])] > 0) return true;
    const int32_t j = who_[at(t - 1, p[t])];  // swap: j goes p[t] -> p[t - 1]
    if (p[t] != p[t - 1] && j >= 0 && j != i && in_tables(j) && path(j)[t] == p[t - 1]) return true;
  }
  return false;
}

void LocalGuidance::hold(int32_t i)
{
  if (refresh_ > 0 && planned(i) && !marked_[i]) mark(i);
}

void LocalGuidance::unmark(int32_t i)
{
  const Vertex* p = path(i);
  for (int t = 1; t <= w_; ++t) {
    uint16_t& c = cnt_[at(t, p[t])];
    if (c > 0) --c;
    if (who_[at(t, p[t])] == i) who_[at(t, p[t])] = -1;
  }
  marked_[i] = 0;
}

void LocalGuidance::plan(int32_t i)
{
  if (++call_ == 0) std::fill(closed_.begin(), closed_.end(), 0), call_ = 1;
  const Vertex goal = goals_[i];
  if (refresh_ > 0) {
    if (marked_[i]) unmark(i);  // a stale path, planned again
    age_[i] = 0;
  }
  if (rest_ && from_[i] == goal) {  // resting on its goal: it stays (PIBT moves it if pushed)
    Vertex* p = paths_.data() + static_cast<size_t>(i) * (w_ + 1);
    std::fill(p, p + w_ + 1, goal);
    stamp_of_[i] = round_;
    mark(i);
    return;
  }
  // Key: collisions, then f = g + h, then deeper first (ties end sooner).
  auto key = [&](const Node& x) {
    const uint64_t c = std::min<uint64_t>(static_cast<uint64_t>(x.coll), (uint64_t{1} << 20) - 1);
    const uint64_t f = std::min<uint64_t>(static_cast<uint64_t>(x.g) + static_cast<uint64_t>(d_.get(i, x.v)),
                                          (uint64_t{1} << 28) - 1);
    if (weight_ > 0) {  // one sum: a collision is worth weight_ steps (ties: fewer collisions)
      const uint64_t s = std::min<uint64_t>(f + static_cast<uint64_t>(weight_) * c, (uint64_t{1} << 28) - 1);
      return (s << 36) | (std::min<uint64_t>(c, (uint64_t{1} << 20) - 1) << 16) | static_cast<uint64_t>(0xFFFF - x.t);
    }
    return (c << 44) | (f << 16) | static_cast<uint64_t>(0xFFFF - x.t);
  };
  auto cmp = std::greater<std::pair<uint64_t, int32_t>>();
  nodes_.clear();
  open_.clear();
  nodes_.push_back(Node{from_[i], 0, -1, 0, 0});
  open_.emplace_back(key(nodes_[0]), 0);
  int32_t best = 0;  // the deepest, then cheapest, node popped (kept if the A* is cut)
  int32_t found = -1;
  while (!open_.empty()) {
    std::pop_heap(open_.begin(), open_.end(), cmp);
    const int32_t k = open_.back().second;
    open_.pop_back();
    const Node x = nodes_[k];
    uint32_t& cl = closed_[at(x.t, x.v)];
    if (cl == call_) continue;
    cl = call_;
    if (x.t > nodes_[best].t) best = k;
    if (x.t == w_) {
      found = k;
      break;
    }
    if (nodes_.size() >= static_cast<size_t>(kMaxNodes)) break;
    const int t1 = x.t + 1;
    auto push = [&](Vertex u) {
      if (closed_[at(t1, u)] == call_) return;
      int32_t coll = x.coll + cnt_[at(t1, u)];
      if (unplanned_ && t1 == 1) {  // an unplanned agent there now
        const int32_t j0 = who_[at(0, u)];
        if (j0 >= 0 && j0 != i && !in_tables(j0)) ++coll;
      }
      const int32_t j = who_[at(x.t, u)];  // swap: j goes u -> x.v while i goes x.v -> u
      if (u != x.v && j >= 0 && j != i && in_tables(j) && paths_[static_cast<size_t>(j) * (w_ + 1) + t1] == x.v) ++coll;
      const int32_t g = x.g + ((x.v == goal && u == goal) ? 0 : 1);
      nodes_.push_back(Node{u, t1, k, g, coll});
      open_.emplace_back(key(nodes_.back()), static_cast<int32_t>(nodes_.size() - 1));
      std::push_heap(open_.begin(), open_.end(), cmp);
    };
    for (Vertex u : g_.neighbors(x.v)) push(u);
    push(x.v);
  }
  if (first_share_ < 0) {  // the first N paths: how many are slowed by the others (first_conflicted)
    const Node& e = nodes_[found >= 0 ? found : best];
    first_hit_ += e.coll > 0 || e.g + d_.get(i, e.v) > d_.get(i, from_[i]);
    if (++first_planned_ >= n_) first_share_ = static_cast<double>(first_hit_) / first_planned_;
  }
  nodes_total_ += nodes_.size();
  round_nodes_ += nodes_.size();
  // The path, padded by staying where a cut A* stopped.
  Vertex* p = paths_.data() + static_cast<size_t>(i) * (w_ + 1);
  int32_t k = found >= 0 ? found : best;
  const int tk = nodes_[k].t;
  for (int t = w_; t > tk; --t) p[t] = nodes_[k].v;
  for (; k >= 0; k = nodes_[k].parent) p[nodes_[k].t] = nodes_[k].v;
  stamp_of_[i] = round_;
  mark(i);
}

}  // namespace planner
