#include "planner/dist_cache.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "planner/budget.hpp"

namespace planner {

namespace {
constexpr size_t kChunk = 64;   // BFS vertices between clock reads (10-20 us at most on WAREHOUSE)
constexpr size_t kSpare = 16;   // dropped tables kept for reuse
}

DistCache::Table::Table(const Graph& g, Vertex goal_vertex, DistCache* cache)
    : dist(g.size(), kInf), goal(goal_vertex), owner(cache), weighted(g.weighted() || (cache && cache->arc_costs()))
{
  if (cache && cache->arc_costs()) extra = cache->extra_.data();
  if (!weighted) {
    dist[goal] = 0;
    queue.push_back(goal);
    return;
  }
  buckets.resize(static_cast<size_t>(g.max_move_cost() + (cache ? cache->max_extra() : 0)) + 1);
  restart(goal_vertex);
}

void DistCache::Table::restart(Vertex goal_vertex)
{
  std::fill(dist.begin(), dist.end(), kInf);
  queue.clear();
  head = 0;
  goal = goal_vertex;
  pins = 0;
  used = 0;
  missed = false;
  popped = 0;
  dist[goal] = 0;
  if (!weighted) {
    queue.push_back(goal);
    return;
  }
  // The goal is settled at 0 (dist) and popped first, from bucket 0.
  tent.assign(dist.size(), kInf);
  for (auto& b : buckets) b.clear();
  tent[goal] = 0;
  buckets[0].push_back(goal);
  cur = 0;
  open = 1;
}

void DistCache::Table::finish()
{
  if (weighted) {
    if (!tent.empty()) std::vector<int32_t>().swap(tent);
    for (auto& b : buckets) std::vector<Vertex>().swap(b);
    return;
  }
  if (!queue.empty()) std::vector<Vertex>().swap(queue), head = 0;
}

void DistCache::Table::pop_weighted(const Graph& g)
{
  const size_t nb = buckets.size();
  while (buckets[static_cast<size_t>(cur) % nb].empty()) ++cur;  // open > 0: ends within nb buckets
  std::vector<Vertex>& b = buckets[static_cast<size_t>(cur) % nb];
  const Vertex u = b.back();
  b.pop_back();
  --open;
  ++popped;
  // Entries are pushed only when a tentative distance drops, so an entry whose distance is
  // no longer u's is stale (u went into a nearer bucket and was settled from there).
  if (tent[u] != cur) return;
  dist[u] = cur;
  // Distances *to* the goal: a move w -> u costs u's cost (+ the arc's extra cost).
  const int32_t d0 = cur + g.move_cost(u);
  const auto in = g.in_neighbors(u);
  const uint8_t* x = extra ? extra + g.in_arc(u) : nullptr;
  for (size_t k = 0; k < in.size(); ++k) {
    const Vertex w = in[k];
    const int32_t d = x ? d0 + x[k] : d0;
    if (dist[w] != kInf || tent[w] <= d) continue;
    tent[w] = d;
    buckets[static_cast<size_t>(d) % nb].push_back(w);
    ++open;
  }
}

void DistCache::Table::compact()
{
  if (weighted) return;  // the ring holds only entries near the popped distance
  // The popped prefix of the queue is dead: keep the open frontier only (a ring of a few
  // hundred vertices, against up to |V| discovered), so a partly grown table costs about
  // its distance array.
  if (head < 4096 || 2 * head < queue.size()) return;
  queue.erase(queue.begin(), queue.begin() + static_cast<long>(head));
  head = 0;
  if (queue.capacity() > 2 * queue.size() + 4096) queue.shrink_to_fit();
}

void DistCache::Table::pop(const Graph& g)
{
  if (weighted) return pop_weighted(g);
  const Vertex u = queue[head++];
  ++popped;
  // Distances *to* the goal: the BFS walks arcs backwards (in-neighbours; the same as
  // out-neighbours on an undirected graph).
  for (Vertex w : g.in_neighbors(u)) {
    if (dist[w] != kInf) continue;
    dist[w] = dist[u] + 1;
    queue.push_back(w);
  }
}

int32_t DistCache::Table::extend_until(Vertex v, const Graph& g)
{
  // Vertices get their distance when discovered, so stop as soon as v is discovered.
  while (!done()) {
    pop(g);
    if (dist[v] != kInf) {
      compact();
      return dist[v];
    }
  }
  finish();     // search done: free the queue
  return kInf;  // v is unreachable
}

bool DistCache::Table::grow_until(Vertex v, size_t pops, const Graph& g)
{
  for (; pops > 0 && dist[v] == kInf && !done(); --pops) pop(g);
  if (done()) finish();  // search done
  compact();
  return dist[v] != kInf || done();
}

int32_t DistCache::Table::query(Vertex v, const Graph& g)
{
  if (done()) return kInf;  // finished BFS: v is unreachable
  const uint64_t p0 = popped;
  if (!owner || !owner->bounded()) {
    const int32_t d = extend_until(v, g);
    if (owner) owner->counters_.query_pops += popped - p0;
    return d;
  }
  // Grow towards v in chunks while the deadline allows; one clock read per chunk.
  while (!owner->expired_) {
    if (Clock::now() >= owner->deadline_) {
      owner->expired_ = true;
      break;
    }
    if (grow_until(v, kChunk, g)) {
      owner->counters_.query_pops += popped - p0;
      return dist[v];  // kInf if the BFS finished without reaching v
    }
  }
  owner->counters_.query_pops += popped - p0;
  owner->note_miss(*this, v);
  return lower_bound(v, g);
}

int32_t DistCache::Table::lower_bound(Vertex v, const Graph& g) const
{
  if (dist[v] != kInf) return dist[v];
  if (done()) return kInf;
  // BFS: the queue is in BFS order, so every vertex nearer than its head's distance + 1 has
  // been discovered; an undiscovered one is at least that far. Dijkstra: an unsettled
  // vertex is at least the popped bucket's distance away, and v is not the goal (settled).
  int32_t d = weighted ? std::max<int32_t>(cur, 1) : dist[queue[head]] + 1;
  if (g.is_grid())  // every arc joins 4-neighbours, each move costs >= 1: Manhattan is a lower bound too (one-way arcs only lengthen paths)
    d = std::max(d, std::abs(g.cell_x(v) - g.cell_x(goal)) + std::abs(g.cell_y(v) - g.cell_y(goal)));
  return d;
}

void DistCache::note_miss(Table& t, Vertex v)
{
  ++counters_.estimates;
  if (t.missed) return;
  t.missed = true;
  missed_.push_back({t.goal, v});
}

void DistCache::set_arc_costs(std::vector<uint8_t> extra)
{
  if (!tables_.empty() || !spare_.empty()) throw std::logic_error("DistCache::set_arc_costs after a table was made");
  extra_ = std::move(extra);
  max_extra_ = 0;
  for (uint8_t c : extra_) max_extra_ = std::max<int>(max_extra_, c);
  if (max_extra_ == 0) extra_.clear();
}

DistCache::Table* DistCache::table(Vertex goal)
{
  auto it = by_goal_.find(goal);
  if (it != by_goal_.end()) return it->second;
  if (spare_.empty()) {
    tables_.push_back(std::make_unique<Table>(g_, goal, this));
  } else {
    tables_.push_back(std::move(spare_.back()));
    spare_.pop_back();
    tables_.back()->restart(goal);
  }
  return by_goal_[goal] = tables_.back().get();
}

void DistCache::trim()
{
  if (max_tables_ == 0 || tables_.size() <= max_tables_) return;
  // Pinned tables first, then by recency; drop the tail beyond the cap (pinned never).
  auto keep_first = [](const std::unique_ptr<Table>& a, const std::unique_ptr<Table>& b) {
    if ((a->pins > 0) != (b->pins > 0)) return a->pins > 0;
    return a->used > b->used;
  };
  std::nth_element(tables_.begin(), tables_.begin() + static_cast<long>(max_tables_), tables_.end(), keep_first);
  size_t keep = max_tables_;
  for (size_t k = keep; k < tables_.size(); ++k)
    if (tables_[k]->pins > 0) std::swap(tables_[k], tables_[keep++]);
  for (size_t k = keep; k < tables_.size(); ++k) {
    by_goal_.erase(tables_[k]->goal);
    if (spare_.size() < kSpare) spare_.push_back(std::move(tables_[k]));
  }
  tables_.resize(keep);
}

bool DistCache::met(const Table& t, Vertex from) const { return unmet(t, from) < 0; }

Vertex DistCache::unmet(const Table& t, Vertex from) const
{
  if (t.done()) return -1;
  if (t.dist[from] == kInf) return from;
  for (Vertex w : g_.neighbors(from))
    if (t.dist[w] == kInf) return w;
  return -1;
}

bool DistCache::grow_chunk(Table& t, Vertex from)
{
  const Vertex need = unmet(t, from);
  if (need < 0) return false;
  const uint64_t p0 = t.popped;
  t.grow_until(need, kChunk, g_);
  counters_.precompute_pops += t.popped - p0;
  return true;
}

void DistCache::prefetch(const std::vector<Want>& wants)
{
  std::vector<std::pair<Table*, Vertex>> next;
  next.reserve(wants.size());
  for (const Want& w : wants) {
    Table* t = table(w.goal);
    if (met(*t, w.from)) {
      t->used = ++tick_;  // ready: just keep it recent
      continue;
    }
    pin(t);
    next.push_back({t, w.from});
  }
  for (const auto& [t, from] : wanted_) unpin(t);
  wanted_ = std::move(next);
  wanted_head_ = 0;
  trim();
}

bool DistCache::precompute(Deadline deadline)
{
  // Tables in use that a query found short (most recent first; dropped ones are skipped).
  while (!missed_.empty()) {
    const auto [goal, v] = missed_.back();
    auto it = by_goal_.find(goal);
    if (it == by_goal_.end() || !grow_chunk(*it->second, v)) {
      if (it != by_goal_.end()) it->second->missed = false;
      missed_.pop_back();
      continue;
    }
    if (Clock::now() >= deadline) return pending() > 0;
  }
  while (wanted_head_ < wanted_.size()) {
    if (!grow_chunk(*wanted_[wanted_head_].first, wanted_[wanted_head_].second)) {
      ++wanted_head_;
      continue;
    }
    if (Clock::now() >= deadline) return pending() > 0;
  }
  return false;
}

size_t DistCache::bytes() const
{
  size_t b = 0;
  auto of = [](const Table& t) {
    size_t n = t.dist.capacity() * sizeof(int32_t) + t.queue.capacity() * sizeof(Vertex) + t.tent.capacity() * sizeof(int32_t);
    for (const auto& q : t.buckets) n += q.capacity() * sizeof(Vertex);
    return n;
  };
  for (const auto& t : tables_) b += of(*t);
  for (const auto& t : spare_) b += of(*t);
  return b;
}

}  // namespace planner
