#include "planner/lacam/scatter.hpp"

#include <algorithm>
#include <numeric>

namespace planner {

namespace {
// Heap order: fewer collisions first, then smaller f, then deeper (closer to the goal), all
// in one integer (Node::key): one comparison instead of three, the same order.
template <class N>
bool worse(const N& a, const N& b)
{
  return a.key > b.key;
}
}  // namespace

uint64_t Scatter::key(int64_t coll, int32_t f, int32_t g) const
{
  const uint64_t c = std::min<uint64_t>(static_cast<uint64_t>(coll), coll_max_);
  return (c << (2 * len_bits_)) | (static_cast<uint64_t>(f) << len_bits_) | (len_max_ - static_cast<uint64_t>(g));
}

void Scatter::clear()
{
  // body_ and last_ (per vertex, per step: who is there) are kept for the next reset(): every
  // entry belongs to a path in paths_, so emptying those cells empties them, in O(the paths'
  // length). Dropping and rebuilding them (|V| lists of up to T lists each) took 4-8 ms in one
  // refinement step at N = 1000 (warehouse-20-40-10-2-2), when SUO restarted further ahead.
  for (const auto& p : paths_) {
    for (size_t t = 0; t < p.size(); ++t)
      if (static_cast<size_t>(p[t]) < body_.size() && t < body_[p[t]].size()) body_[p[t]][t] = -1;
    if (!p.empty() && static_cast<size_t>(p.back()) < last_.size()) last_[p.back()].clear();
  }
  cells_.clear();
  free_cell_ = -1;
  n_ = 0;
  done_ = true;
  in_astar_ = false;
  paths_.clear();
  published_.clear();
  next_.clear();
  staged_ = 0;
  passes_ = 0;
  collisions_ = published_collisions_ = 0;
}

bool Scatter::prepare(Clock::time_point deadline)
{
  const size_t V = static_cast<size_t>(g_.size());
  if (prepared()) return true;
  if (body_.size() > V || last_.size() != body_.size() || parent_.size() != body_.size())
    body_.clear(), last_.clear(), parent_.clear();
  body_.reserve(V), last_.reserve(V), parent_.reserve(V);  // not touched yet: no page costs
  while (body_.size() < V) {
    const size_t end = std::min(V, body_.size() + kPrepareChunk);
    body_.resize(end), last_.resize(end), parent_.resize(end, -2);
    if (Clock::now() >= deadline) break;
  }
  if (body_.size() < V) return false;
  ++occupancy_builds_;
  return true;
}

bool Scatter::prepared() const
{
  const size_t V = static_cast<size_t>(g_.size());
  return body_.size() == V && last_.size() == V && parent_.size() == V;
}

void Scatter::reset(const Config& starts, int margin, uint64_t seed, int max_passes)
{
  clear();
  max_passes_ = max_passes;
  bucket_ = bucket_next_;
  n_ = static_cast<int>(starts.size());
  margin_ = margin;
  rng_ = Rng(seed);
  starts_ = starts;
  paths_.assign(n_, {});
  const size_t V = static_cast<size_t>(g_.size());
  if (body_.size() != V) body_.assign(V, {}), ++occupancy_builds_;  // else emptied by clear()
  if (last_.size() != V) last_.assign(V, {});
  parent_.assign(g_.size(), -2);
  // f, g <= distance + margin < |V| + margin + 1: len_bits_ bits each, the rest for collisions.
  len_bits_ = 1;
  while ((uint64_t{1} << len_bits_) <= g_.size() + static_cast<uint64_t>(margin) + 1) ++len_bits_;
  len_max_ = (uint64_t{1} << len_bits_) - 1;
  coll_max_ = (uint64_t{1} << (64 - 2 * len_bits_)) - 1;
  order_.resize(n_);
  std::iota(order_.begin(), order_.end(), 0);
  rng_.shuffle(order_.data(), n_);
  pos_ = 0;
  pass_start_collisions_ = 0;
  done_ = n_ == 0;
}

int32_t Scatter::count(int32_t head) const
{
  int32_t c = 0;
  for (; head >= 0; head = cells_[head].next) ++c;
  return c;
}

void Scatter::occupy(Vertex v, int32_t t, int i)
{
  auto& b = body_[v];
  if (b.size() <= static_cast<size_t>(t)) b.resize(t + 1, -1);
  int32_t k = free_cell_;
  if (k >= 0)
    free_cell_ = cells_[k].next;
  else
    k = static_cast<int32_t>(cells_.size()), cells_.emplace_back();
  cells_[k] = Cell{i, b[t]};
  b[t] = k;
}

void Scatter::vacate(Vertex v, int32_t t, int i)
{
  int32_t* link = &body_[v][t];
  while (cells_[*link].agent != i) link = &cells_[*link].next;
  const int32_t k = *link;
  *link = cells_[k].next;
  cells_[k].next = free_cell_;
  free_cell_ = k;
}

int32_t Scatter::collision_cost(Vertex u, Vertex w, int32_t t) const
{
  int32_t c = 0;
  const auto& bw = body_[w];
  const auto& bu = body_[u];
  if (static_cast<size_t>(t + 1) < bw.size()) c += count(bw[t + 1]);                // vertex
  if (static_cast<size_t>(t + 1) < bu.size() && static_cast<size_t>(t) < bw.size())  // swap
    for (int32_t j = bu[t + 1]; j >= 0; j = cells_[j].next)
      for (int32_t k = bw[t]; k >= 0; k = cells_[k].next)
        c += cells_[j].agent == cells_[k].agent;
  for (int32_t arrived : last_[w]) c += t + 1 > arrived;  // on somebody's goal after they arrived
  return c;
}

// The collisions of agent i's path with everybody else's (i not enrolled): pairwise and
// symmetric, so enroll adds and withdraw subtracts the same amount.
void Scatter::enroll(int i)
{
  const auto& p = paths_[i];
  if (p.empty()) return;
  const int32_t T = static_cast<int32_t>(p.size()) - 1;
  int64_t c = 0;
  for (int32_t t = 0; t < T; ++t) c += collision_cost(p[t], p[t + 1], t);
  const auto& bg = body_[p.back()];
  for (size_t t = T + 1; t < bg.size(); ++t) c += count(bg[t]);
  collisions_ += c;
  for (int32_t t = 0; t <= T; ++t) occupy(p[t], t, i);
  last_[p.back()].push_back(T);
  work_ += 2 * (T + 1);
}

void Scatter::withdraw(int i)
{
  const auto& p = paths_[i];
  if (p.empty()) return;
  const int32_t T = static_cast<int32_t>(p.size()) - 1;
  for (int32_t t = 0; t <= T; ++t) vacate(p[t], t, i);
  auto& l = last_[p.back()];
  l.erase(std::find(l.begin(), l.end(), T));
  int64_t c = 0;
  for (int32_t t = 0; t < T; ++t) c += collision_cost(p[t], p[t + 1], t);
  const auto& bg = body_[p.back()];
  for (size_t t = T + 1; t < bg.size(); ++t) c += count(bg[t]);
  collisions_ -= c;
  work_ += 2 * (T + 1);
}

// Open list. Heap: std::push_heap / pop_heap on the key. Bucket queue: one bucket per
// (collisions, f) level, levels are popped in increasing order (along an edge neither
// collisions nor f -- consistent heuristic -- decrease, so nothing is ever pushed below the
// level being popped); inside the level the deepest node first: the bucket is sorted by
// key once when it is reached, and every child pushed into it is one deeper than the node
// just popped, the deepest there, so a push to the back keeps it sorted. The same order
// as the heap up to ties between equal keys.
size_t Scatter::level(const Node& x) const
{
  const uint64_t coll = x.key >> (2 * len_bits_);
  const int32_t f = static_cast<int32_t>((x.key >> len_bits_) & len_max_);
  const int64_t l = static_cast<int64_t>(coll) * (margin_ + 1) + (f - f0_);
  return static_cast<size_t>(std::max<int64_t>(l, 0));
}

void Scatter::push(const Node& x)
{
  if (!bucket_) {
    open_.push_back(x);
    std::push_heap(open_.begin(), open_.end(), [](const Node& a, const Node& b) { return worse(a, b); });
    return;
  }
  // Below the level being popped only with an inconsistent distance (a lower bound past
  // the BFS's deadline): then into the current level, in its order.
  const size_t l = std::max(std::min(level(x), kMaxLevels - 1), cur_);
  if (l >= buckets_.size()) buckets_.resize(l + 1);
  auto& b = buckets_[l];
  if (l == cur_ && level_sorted_ && !b.empty() && !worse(b.back(), x))
    b.insert(std::upper_bound(b.begin(), b.end(), x, [](const Node& a, const Node& c) { return worse(a, c); }), x);
  else
    b.push_back(x);
  top_ = std::max(top_, l + 1);
}

bool Scatter::open_empty()
{
  if (!bucket_) return open_.empty();
  while (cur_ < top_ && buckets_[cur_].empty()) {
    ++cur_;
    level_sorted_ = false;
  }
  return cur_ >= top_;
}

Scatter::Node Scatter::pop()  // after !open_empty()
{
  if (!bucket_) {
    std::pop_heap(open_.begin(), open_.end(), [](const Node& a, const Node& b) { return worse(a, b); });
    const Node x = open_.back();
    open_.pop_back();
    return x;
  }
  auto& b = buckets_[cur_];
  if (!level_sorted_) {
    std::sort(b.begin(), b.end(), [](const Node& x, const Node& y) { return worse(x, y); });
    level_sorted_ = true;
  }
  const Node x = b.back();
  b.pop_back();
  return x;
}

void Scatter::begin_agent()
{
  const int i = order_[pos_];
  withdraw(i);
  const Vertex s = starts_[i];
  cost_ub_ = dist_.get(i, s) + margin_;
  open_.clear();
  for (size_t b = 0; b < top_; ++b) buckets_[b].clear();
  cur_ = top_ = 0;
  level_sorted_ = false;
  f0_ = dist_.get(i, s);
  push(Node{key(0, f0_, 0), s, -1});
  in_astar_ = true;
}

bool Scatter::run_astar(Clock::time_point deadline, uint64_t max_work)
{
  const int i = order_[pos_];
  const Vertex s = starts_[i];
  uint64_t pops = 0;
  bool solved = false;
  Vertex goal = -1;
  while (!open_empty()) {
    if ((++pops & 63) == 0 && (work_ >= max_work || Clock::now() >= deadline)) return false;
    const Node x = pop();
    work_ += 4;
    if (parent_[x.v] != -2) continue;
    parent_[x.v] = x.parent;
    closed_.push_back(x.v);
    if (dist_.get(i, x.v) == 0) {
      solved = true;
      goal = x.v;
      break;
    }
    const int64_t coll = static_cast<int64_t>(x.key >> (2 * len_bits_));
    const int32_t g = static_cast<int32_t>(len_max_ - (x.key & len_max_));
    for (Vertex u : g_.neighbors(x.v)) {
      if (u == s || parent_[u] != -2) continue;
      const int32_t d = dist_.get(i, u);
      if (g + 1 + d > cost_ub_) continue;
      push(Node{key(coll + collision_cost(x.v, u, g), g + 1 + d, g + 1), u, x.v});
    }
  }
  auto& p = paths_[i];
  if (solved) {
    p.clear();
    for (Vertex v = goal; v != -1; v = parent_[v]) p.push_back(v);
    std::reverse(p.begin(), p.end());
  } else if (p.empty()) {
    // Closing vertices by collision count can cut every route within the margin; a
    // shortest path (down the distance table) keeps every agent guided.
    p.push_back(s);
    for (Vertex v = s; dist_.get(i, v) > 0 && dist_.get(i, v) < DistTable::kInf;) {
      for (Vertex u : g_.neighbors(v))
        if (dist_.get(i, u) < dist_.get(i, v)) {
          v = u;
          break;
        }
      p.push_back(v);
    }
  }
  for (Vertex v : closed_) parent_[v] = -2;
  closed_.clear();
  open_.clear();
  for (size_t b = 0; b < top_; ++b) buckets_[b].clear();
  cur_ = top_ = 0;
  level_sorted_ = false;
  enroll(i);
  if (live_ && passes_ == 0) show(i);
  in_astar_ = false;
  return true;
}

// The first pass's path of agent i as guidance now (its sorted successor list, what
// publish() builds for every agent at the pass's end): O(its length x log).
void Scatter::show(int i)
{
  if (next_.size() != static_cast<size_t>(n_)) next_.assign(n_, {});
  const auto& p = paths_[i];
  auto& nx = next_[i];
  nx.clear();
  for (size_t t = 0; t + 1 < p.size(); ++t) nx.emplace_back(p[t], p[t + 1]);
  std::sort(nx.begin(), nx.end());
  work_ += p.size();
}

void Scatter::end_pass()
{
  publish(Clock::time_point::max());
}

// The pass is published into staging copies agent by agent (the guidance in use stays whole
// until they are swapped in): O(the paths' cells) in all, 0.4-2 ms at once for N = 600-1000.
bool Scatter::publish(Clock::time_point deadline)
{
  if (passes_ == 0 || collisions_ <= published_collisions_) {  // a better pass (the first one)
    staged_paths_.resize(n_);
    staged_next_.resize(n_);
    while (staged_ < n_) {
      const int i = staged_++;
      const auto& p = paths_[i];
      staged_paths_[i] = p;
      auto& nx = staged_next_[i];
      nx.clear();
      for (size_t t = 0; t + 1 < p.size(); ++t) nx.emplace_back(p[t], p[t + 1]);
      std::sort(nx.begin(), nx.end());
      work_ += p.size();
      if ((staged_ & 15) == 0 && staged_ < n_ && Clock::now() >= deadline) return false;
    }
    published_.swap(staged_paths_);
    next_.swap(staged_next_);
    published_collisions_ = collisions_;
  }
  staged_ = 0;
  ++passes_;
  // lacam3: at least two passes, then on while the collision count drops.
  if (collisions_ == 0 || (max_passes_ > 0 && passes_ >= max_passes_) || (passes_ >= 2 && collisions_ >= pass_start_collisions_)) {
    done_ = true;
    return true;
  }
  pass_start_collisions_ = collisions_;
  pos_ = 0;
  rng_.shuffle(order_.data(), n_);
  return true;
}

bool Scatter::step(Clock::time_point deadline, uint64_t max_work, bool end_passes)
{
  work_ = 0;
  while (!done_ && pos_ < n_) {
    if (!in_astar_) begin_agent();
    if (!run_astar(deadline, max_work)) break;  // paused inside the A*
    if (++pos_ == n_) {
      if (!end_passes) break;
      end_pass();
    }
    if (work_ >= max_work || Clock::now() >= deadline) break;
  }
  return done_;
}

Vertex Scatter::next(int i, Vertex v) const
{
  if (next_.empty()) return -1;
  const auto& nx = next_[i];
  auto it = std::lower_bound(nx.begin(), nx.end(), std::make_pair(v, Vertex{-1}));
  return it != nx.end() && it->first == v ? it->second : -1;
}

}  // namespace planner
