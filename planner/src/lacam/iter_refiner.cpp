#include "planner/lacam/iter_refiner.hpp"

#include <algorithm>
#include <climits>

namespace planner {

namespace {
constexpr int kMaxGroup = 30;        // lacam3's largest group
constexpr size_t kMaxNodes = 200000; // a failing A* gives up here (its bound prunes most)
}  // namespace

void IterRefiner::begin(const std::vector<const Vertex*>& path, int n, int64_t step0, const Config& goals,
                        uint64_t version, const int32_t* wait)
{
  // The rows of the copy before that are in the table get cleared first (by build()); an
  // older copy still being cleared is finished here (a copy begun before the last was built).
  const int entered = ready_ ? T_ + 1 : (src_.empty() && n_ == 0 ? 0 : row_);
  if (entered > 0) {
    clear_old(Clock::time_point::max());
    old_.swap(paths_);
    old_n_ = n_;
    old_T_ = entered - 1;
    old_S_ = S_;
    old_row_ = 0;
  }
  src_ = path;
  row_ = 0;
  ready_ = false;
  n_ = n;
  T_ = static_cast<int>(path.size()) - 1;
  V_ = g_.size();
  S_ = static_cast<size_t>(T_ + 1);
  step0_ = step0;
  version_ = version;
  goals_ = goals;
  wait_.assign(n_, 0);
  if (wait) std::copy(wait, wait + n_, wait_.begin());
  if (stamp_.size() != V_) {
    times_.assign(V_, {});
    stamp_.assign(V_, 0);
    first_.assign(V_, 0);
    count_.assign(V_, 0);
    epoch_ = 0;
  }
  arrival_.assign(n_, 0);
  moved_.assign(n_, 0);
  idle_ = 0;
  work_ = static_cast<uint64_t>(T_ + 1);
}

// Clears the old copy's cells (the table keeps its size: zeroing |V| x T would cost more).
bool IterRefiner::clear_old(Clock::time_point deadline)
{
  for (; old_row_ <= old_T_; ++old_row_) {
    if (old_row_ > 0 && (old_row_ & 3) == 0 && Clock::now() >= deadline) return false;
    for (int i = 0; i < old_n_; ++i) {
      const Vertex v = old_[static_cast<size_t>(old_row_) * old_n_ + i];
      occ_[static_cast<size_t>(v) * old_S_ + static_cast<size_t>(old_row_)] = 0;
      times_[v].clear();
    }
    work_ += static_cast<uint64_t>(old_n_);
  }
  return true;
}

bool IterRefiner::build(Clock::time_point deadline)
{
  if (ready_) return true;
  if (!clear_old(deadline)) return false;
  // With headroom: a longer path later does not reallocate (a new table's pages fault in
  // as they are written, lazy_table.hpp).
  if (occ_.size() < S_ * V_) occ_.ensure(2 * S_ * V_);
  // Its pages are mapped ahead, in pieces: entered by rows, the writes scatter over the whole
  // table, and faulting its pages in one by one took a 1 ms step to 1.5 ms (N = 600).
  constexpr size_t kPiece = 16 * LazyTable<int32_t>::kPage / sizeof(int32_t);
  while (occ_.touched() < S_ * V_) {
    occ_.touch(std::min(S_ * V_, occ_.touched() + kPiece));
    if (occ_.touched() < S_ * V_ && Clock::now() >= deadline) return false;
  }
  paths_.resize(static_cast<size_t>(n_) * S_);
  for (; row_ <= T_; ++row_) {
    if (row_ > 0 && (row_ & 3) == 0 && Clock::now() >= deadline) return false;
    const Vertex* C = src_[row_];
    std::copy(C, C + n_, &paths_[static_cast<size_t>(row_) * n_]);
    for (int i = 0; i < n_; ++i) {
      occ(row_, C[i]) = i + 1;
      times_[C[i]].push_back(row_);  // rows ascend: each list stays sorted
      if (C[i] != goals_[i]) arrival_[i] = row_ + 1;
    }
    work_ += static_cast<uint64_t>(n_);
  }
  cost_ = 0;
  for (int i = 0; i < n_; ++i) cost_ += cost_of(i, arrival_[i]);
  emitted_cost_ = cost_;
  dirty_a_ = dirty_b_ = -1;
  if (static_cast<int>(order_.size()) != n_ || next_ >= order_.size()) new_pass();
  src_.clear();
  ready_ = true;
  return true;
}

int IterRefiner::arrival_by(int i, int t) const
{
  for (; t >= 0; --t)
    if (at(i, t) != goals_[i]) return t + 1;
  return 0;
}

void IterRefiner::new_pass()
{
  order_.resize(n_);
  for (int i = 0; i < n_; ++i) order_[i] = i;
  rng_.shuffle(order_.data(), n_);
  next_ = 0;
  const int hi = std::max(1, std::min(kMaxGroup, n_ / 4));
  group_ = 1 + static_cast<int>(rng_.below(static_cast<uint32_t>(hi)));
}

// The free runs of v's steps in [tf, T_]; agent i's own cells count as free (its cell at tf
// is where it starts).
void IterRefiner::intervals(int i, Vertex v, int tf)
{
  stamp_[v] = epoch_;
  first_[v] = static_cast<int32_t>(ivl_.size());
  const std::vector<int32_t>& ts = times_[v];
  int lo = tf;  // the running interval's first free step
  for (auto it = std::lower_bound(ts.begin(), ts.end(), tf); it != ts.end(); ++it) {
    const int t = *it;
    if (occ(t, v) == i + 1) continue;  // its own cell (where it starts) counts as free
    if (t > lo) ivl_.push_back({lo, t - 1, INT32_MAX});
    lo = t + 1;
  }
  if (lo <= T_) ivl_.push_back({lo, T_, INT32_MAX});
  count_[v] = static_cast<int32_t>(ivl_.size()) - first_[v];
}

void IterRefiner::put(int t, Vertex v, int i)
{
  occ(t, v) = i + 1;
  std::vector<int32_t>& ts = times_[v];
  ts.insert(std::upper_bound(ts.begin(), ts.end(), t), t);
}

void IterRefiner::take(int t, Vertex v)
{
  occ(t, v) = 0;
  std::vector<int32_t>& ts = times_[v];
  const auto it = std::lower_bound(ts.begin(), ts.end(), t);
  if (it != ts.end() && *it == t) ts.erase(it);
}

bool IterRefiner::replan(int i, int tf, int64_t bound, std::vector<Vertex>& out, Clock::time_point deadline)
{
  const Vertex goal = goals_[i], v0 = at(i, tf);
  out.assign(static_cast<size_t>(T_ - tf + 1), goal);
  int free_from = T_;  // the goal is free of others from here to T_
  while (free_from > tf && occ(free_from - 1, goal) == 0) --free_from;
  if (v0 == goal && free_from <= tf) {  // stays: its arrival is its prefix's
    const int p = arrival_by(i, tf);
    return p == 0 || p <= bound;
  }
  // It arrives at free_from at the earliest: f = max(t + d, free_from) is admissible, and a
  // search that cannot beat its bound ends here instead of sweeping every state below it.
  if (free_from > bound) return false;
  // Its old path already arrives at free_from: the least arrival there is. Kept if the
  // group's earlier members left it free (a search would sweep every state below free_from).
  if (arrival_[i] > tf && arrival_[i] <= free_from && arrival_[i] <= bound) {
    bool free = true;
    for (int t = tf; t < T_ && free; ++t) {
      const Vertex v = at(i, t), u = at(i, t + 1);
      const int32_t o = occ(t + 1, u);
      free = o == 0 || o == i + 1;
      if (free && u != v) {
        const int32_t j = occ(t, u);
        free = j == 0 || j == i + 1 || occ(t + 1, v) != j;
      }
    }
    if (free) {
      for (int t = tf; t <= T_; ++t) out[t - tf] = at(i, t);
      return true;
    }
  }
  if (++epoch_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    epoch_ = 1;
  }
  ivl_.clear();
  nodes_.clear();
  open_ = {};
  // Ties in f (every state below free_from has f = free_from) go to the state nearest the
  // goal, then the latest: the search heads for the goal's neighbourhood to wait there.
  auto key = [&](int64_t f, int d, int t) {
    return (f << 40) | (static_cast<int64_t>(d) << 20) | static_cast<int64_t>(0xFFFFF - t);
  };
  intervals(i, v0, tf);
  if (count_[v0] == 0 || ivl_[first_[v0]].lo != tf) return false;  // cannot happen: its own cell
  ivl_[first_[v0]].best = tf;
  nodes_.push_back({v0, tf, first_[v0], -1});
  open_.push({key(std::max(tf + dist_.get(i, v0), free_from), dist_.get(i, v0), tf), 0});
  while (!open_.empty() && nodes_.size() < kMaxNodes) {
    if ((++clock_ & 63) == 0 && Clock::now() >= deadline) break;
    const int32_t idx = open_.top().second;
    open_.pop();
    const Node n = nodes_[idx];
    if (ivl_[n.ivl].best < n.t) continue;  // reached earlier since
    const int hi = ivl_[n.ivl].hi;         // it may wait here up to hi
    if (n.v == goal && hi == T_) {         // the goal's last interval: it stays
      int32_t k = idx;
      int upto = T_;  // fill each node's vertex from its arrival up to the next arrival - 1
      while (k >= 0) {
        const Node& m = nodes_[k];
        for (int t = m.t; t <= upto; ++t) out[t - tf] = m.v;
        upto = m.t - 1;
        k = m.parent;
      }
      return true;
    }
    const auto nb = g_.neighbors(n.v);
    for (size_t m = 0; m < nb.size(); ++m) {
      const Vertex u = nb[m];
      const int du = dist_.get(i, u);
      if (n.t + 1 + du > bound || n.t + 1 + du > T_) continue;  // too late already
      if (stamp_[u] != epoch_) intervals(i, u, tf);
      for (int32_t s = first_[u], e = first_[u] + count_[u]; s < e; ++s) {
        Interval& I = ivl_[s];
        if (I.hi < n.t + 1) continue;
        if (I.lo > hi + 1) break;
        // the earliest departure tau in [max(t, lo - 1), min(hi, I.hi - 1)] without a swap
        int t = -1;
        for (int tau = std::max(n.t, I.lo - 1), last = std::min(hi, I.hi - 1); tau <= last; ++tau) {
          const int32_t j = occ(tau, u);
          if (j != 0 && j != i + 1 && occ(tau + 1, n.v) == j) continue;  // swap
          t = tau + 1;
          break;
        }
        if (t < 0 || t >= I.best) continue;
        const int64_t f = std::max(t + du, free_from);
        if (f > bound || t + du > T_) continue;
        I.best = t;
        nodes_.push_back({u, t, s, idx});
        open_.push({key(f, du, t), static_cast<int32_t>(nodes_.size() - 1)});
      }
    }
  }
  return false;
}

bool IterRefiner::step(int64_t from, Clock::time_point deadline, int max_agents)
{
  last_group_ = 0;
  if (!ready_) return false;
  const int tf = static_cast<int>(std::max<int64_t>(0, from - step0_));
  if (tf >= T_ - 1) return false;
  if (next_ >= order_.size()) new_pass();
  const size_t end = std::min(order_.size(), next_ + static_cast<size_t>(std::max(1, std::min(group_, max_agents))));
  const std::vector<int> set(order_.begin() + static_cast<std::ptrdiff_t>(next_), order_.begin() + static_cast<std::ptrdiff_t>(end));
  next_ = end;
  ++groups_;
  last_group_ = static_cast<int>(set.size());
  const int64_t cost_before = cost_;
  idle_ += static_cast<int>(set.size());  // until the group lowers the cost
  int64_t before = 0;
  for (int i : set) before += cost_of(i, arrival_[i]);
  for (int i : set)
    for (int t = tf + 1; t <= T_; ++t) take(t, at(i, t));
  // Lower bounds of the agents not yet replanned: their arrivals cannot be below them.
  std::vector<int64_t> lb(set.size());
  int64_t rest = 0;
  for (size_t m = 0; m < set.size(); ++m) {
    const int i = set[m];
    const Vertex v = at(i, tf);
    lb[m] = v == goals_[i] ? 0 : cost_of(i, tf + dist_.get(i, v));
    rest += lb[m];
  }
  fresh_.resize(set.size());
  std::vector<int32_t> arr(set.size(), 0);
  int64_t after = 0;
  size_t done = 0;
  bool ok = true;
  for (size_t m = 0; m < set.size() && ok; ++m) {
    const int i = set[m];
    rest -= lb[m];
    ok = replan(i, tf, before - after - rest - wait_[i], fresh_[m], deadline);
    if (!ok) break;
    int a = 0;
    for (int t = T_; t > tf; --t)
      if (fresh_[m][t - tf] != goals_[i]) {
        a = t + 1;
        break;
      }
    if (a == 0) a = arrival_by(i, tf);  // on its goal after tf: the prefix decides (tf is fixed)
    arr[m] = a;
    after += cost_of(i, a);
    for (int t = tf + 1; t <= T_; ++t) put(t, fresh_[m][t - tf], i);
    ++done;
  }
  if (ok && after > before) ok = false;
  if (ok) {  // the horizon stays: someone must still arrive at T_
    int last = 0;
    for (size_t m = 0; m < set.size(); ++m) last = std::max(last, arr[m]);
    if (last < T_) {
      std::vector<uint8_t> in(n_, 0);
      for (int i : set) in[i] = 1;
      for (int i = 0; i < n_ && last < T_; ++i)
        if (!in[i]) last = std::max(last, arrival_[i]);
    }
    ok = last >= T_;
  }
  if (!ok) {  // restore the group's old paths
    for (size_t m = 0; m < done; ++m)
      for (int t = tf + 1; t <= T_; ++t) take(t, fresh_[m][t - tf]);
    for (int i : set)
      for (int t = tf + 1; t <= T_; ++t) put(t, at(i, t), i);
    return false;
  }
  for (size_t m = 0; m < set.size(); ++m) {
    const int i = set[m];
    for (int t = tf + 1; t <= T_; ++t) {
      const Vertex v = fresh_[m][t - tf];
      if (at(i, t) == v) continue;
      at(i, t) = v;
      moved_[i] = 1;
      dirty_a_ = dirty_a_ < 0 ? t : std::min(dirty_a_, t);
      dirty_b_ = std::max(dirty_b_, t);
    }
    cost_ += cost_of(i, arr[m]) - cost_of(i, arrival_[i]);
    arrival_[i] = arr[m];
  }
  ++kept_;
  if (cost_ < cost_before) idle_ = 0;
  return true;
}

bool IterRefiner::window(RefineWindow& out)
{
  if (!ready_ || dirty_a_ < 0) return false;
  const int a = dirty_a_, b = dirty_b_;
  out.version = version_;
  out.t0 = step0_ + a - 1;
  out.configs.resize(static_cast<size_t>(b - a + 3));
  for (int t = a - 1; t <= b + 1; ++t) {
    Config& C = out.configs[static_cast<size_t>(t - a + 1)];
    C.resize(n_);
    for (int i = 0; i < n_; ++i) C[i] = at(i, t);
  }
  out.agents.clear();
  for (int i = 0; i < n_; ++i)
    if (moved_[i]) out.agents.push_back(i), moved_[i] = 0;
  dirty_a_ = dirty_b_ = -1;
  emitted_cost_ = cost_;
  return true;
}

}  // namespace planner
