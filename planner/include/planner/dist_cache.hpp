#pragma once
// DistCache: BFS distance tables keyed by goal vertex, shared by everyone who needs
// distances to goals on one graph (the planner's DistTable, a heading preference, a task
// assigner): one table per goal cell, however many agents or layers look at it.
//
// A table is a resumable BFS from its goal (lacam3's DistTable grows on demand): a query
// extends it only until the queried vertex is discovered. Lifelong runs know goals before
// they are needed (an agent's next errand): prefetch() queues them and precompute(deadline)
// grows the queued tables in whatever time a step has left, so that an epoch start finds
// them ready instead of paying the BFS in the step it needs them.
//
// Queries run under the cache's deadline (set_deadline; none by default). Before it, a
// query for a vertex the BFS has not reached yet grows the table until it has (checking
// the clock every few hundred vertices): the answer is exact. Past it, no query grows a
// table: it answers with a lower bound (lower_bound()) and notes the table, which the next
// precompute() grows first. So a search expansion never runs a BFS past the step's
// deadline, and the tables catch up in later steps' spare time. What a query returns:
//  - exact: the vertex is discovered (dist[v] < kInf), or the BFS is finished (then kInf
//    means unreachable), or no deadline is set (every query is exact, as before);
//  - a lower bound otherwise: max(frontier depth + 1, Manhattan distance on grid graphs),
//    never above the exact distance (every vertex nearer than the frontier is discovered;
//    grid edges join 4-neighbours) and never 0 off the goal. PIBT only ranks an agent's few
//    candidate cells, so exact near the goal and a lower bound farther out is enough.
//
// Memory is bounded: tables that nobody pins (DistTable::set_goals pins its agents' goals,
// prefetch() pins its queue) are dropped least recently used first once more than
// `max_tables` exist; pinned tables are never dropped, so the cap may be exceeded by them.
// A table costs 4 bytes per vertex (+4 per vertex of its open BFS frontier; the queue is
// compacted as it grows and freed when the BFS finishes). max_tables == 0: no cap.
//
// Weighted graphs (Graph::set_move_costs: a move onto v costs move_cost(v), small integers):
// the table is a resumable Dijkstra instead, with Dial's bucket queue (a ring of
// max_move_cost() + 1 buckets: a relaxed vertex is at most that far above the bucket being
// popped, and no heap is needed). A vertex gets its distance (dist) when it is settled, so
// everything above holds as is: dist[v] < kInf is exact, and an unsettled vertex is at
// least the popped bucket's distance away (and, costs being >= 1, at least Manhattan on a
// grid). The tentative distances take 4 more bytes per vertex until the search finishes.
// Unweighted graphs keep the BFS, unchanged (same distances, same speed).
//
// Arc costs (set_arc_costs; highways.hpp): a cache of its own may add a small cost to some
// arcs (a move against a corridor's grain). Its tables are then Dijkstra tables as above, with
// a move w -> u costing move_cost(u) + its arc's extra cost.
#include <chrono>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "planner/graph.hpp"

namespace planner {

class DistCache {
 public:
  static constexpr int32_t kInf = 1 << 29;  // distance of an unreachable vertex
  using Deadline = std::chrono::steady_clock::time_point;

  struct Table {
    std::vector<int32_t> dist;
    std::vector<Vertex> queue;  // BFS order; [head, end) is the open frontier
    size_t head = 0;
    Vertex goal;
    int pins = 0;        // holders that need it kept
    uint64_t used = 0;   // cache tick of the last pin or prefetch (LRU order)
    DistCache* owner = nullptr;  // whose deadline bounds queries (none: every query exact)
    bool missed = false;         // a query got an estimate; queued for the next precompute
    uint64_t popped = 0;         // BFS vertices popped so far (work counter)
    // Weighted graphs only (Dijkstra): tentative distances, the bucket ring (tentative
    // distance d in bucket d % size; stale entries are skipped), the distance being popped
    // and the entries left in the ring.
    bool weighted = false;
    std::vector<int32_t> tent;
    std::vector<std::vector<Vertex>> buckets;
    int32_t cur = 0;
    size_t open = 0;
    const uint8_t* extra = nullptr;  // per in-arc extra costs (the owner's set_arc_costs), or null
    Table(const Graph& g, Vertex goal, DistCache* owner = nullptr);
    void restart(Vertex goal);  // a fresh BFS from `goal` in this table's memory
    bool done() const { return weighted ? open == 0 : head >= queue.size(); }
    int32_t extend_until(Vertex v, const Graph& g);  // distance of v, growing the BFS as needed
    // Grows the BFS by up to `pops` vertices or until v is discovered; returns whether it is
    // (or the BFS is finished).
    bool grow_until(Vertex v, size_t pops, const Graph& g);
    // Distance of v: exact, or a lower bound past the owner's deadline (see above).
    int32_t at(Vertex v, const Graph& g) { return dist[v] != kInf ? dist[v] : query(v, g); }
    int32_t query(Vertex v, const Graph& g);
    bool exact(Vertex v) const { return dist[v] != kInf || done(); }
    // A lower bound on the distance of an undiscovered v (kInf once the BFS is finished).
    int32_t lower_bound(Vertex v, const Graph& g) const;
    void compact();  // drops the popped part of the queue once it is most of it
    void pop(const Graph& g);  // one BFS step: the next queued vertex labels its unlabelled neighbours
    void pop_weighted(const Graph& g);  // one Dijkstra step: the next bucket entry, settled unless stale
    void finish();  // the search is done: frees its queue
  };

  explicit DistCache(const Graph& g, size_t max_tables = 0) : g_(g), max_tables_(max_tables) {}
  DistCache(const DistCache&) = delete;  // tables point to their cache
  DistCache& operator=(const DistCache&) = delete;
  const Graph& graph() const { return g_; }
  // Extra cost per in-arc (indexed as highway_costs() says); before any table is made
  // (throws std::logic_error after). Empty: none.
  void set_arc_costs(std::vector<uint8_t> extra);
  bool arc_costs() const { return !extra_.empty(); }
  int max_extra() const { return max_extra_; }
  void set_max_tables(size_t n) { max_tables_ = n; }
  size_t max_tables() const { return max_tables_; }

  // The table of `goal`, created on first use. pin/unpin bracket its use by a holder.
  Table* table(Vertex goal);
  void pin(Table* t) { ++t->pins, t->used = ++tick_; }
  void unpin(Table* t) { --t->pins; }
  // Drops least recently used unpinned tables down to the cap. The memory of a few dropped
  // tables is kept for the next new ones: a fresh 4-bytes-per-vertex array is page faults and
  // zeroing (about 40 us on WAREHOUSE's 38,586 cells), several times per lifelong step.
  void trim();

  // A table wanted soon, and the vertex from which it will be queried first (an agent's
  // next goal, from its current goal): it must reach `from` and its neighbours (PIBT's
  // candidates there). Farther vertices are left to the lazy BFS.
  struct Want {
    Vertex goal = -1;
    Vertex from = -1;
  };
  // Replaces the prefetch queue with `wants`, most urgent first (their tables are pinned
  // until the next call).
  void prefetch(const std::vector<Want>& wants);
  // Grows queued tables until every want is met or the deadline passes (checked every few
  // hundred vertices, so it overruns by microseconds): first the tables that queries
  // answered with an estimate (in use now, up to the queried vertex and its neighbours),
  // then the prefetch queue in order. Returns whether work remains.
  bool precompute(Deadline deadline);
  size_t pending() const { return wanted_.size() - wanted_head_ + missed_.size(); }

  // Queries past `d` answer lower bounds instead of growing tables (Deadline::max(): none,
  // every query exact). Setting it clears the expiry seen by the last one.
  void set_deadline(Deadline d) { deadline_ = d, expired_ = false; }
  Deadline deadline() const { return deadline_; }
  bool bounded() const { return deadline_ != Deadline::max(); }

  // Work counters (cumulative): BFS vertices popped inside queries (on the spot) and by
  // precompute(); queries answered with a lower bound.
  struct Counters {
    uint64_t query_pops = 0;
    uint64_t precompute_pops = 0;
    uint64_t estimates = 0;
  };
  const Counters& counters() const { return counters_; }
  size_t missed() const { return missed_.size(); }  // tables queued by estimated queries

  size_t num_tables() const { return tables_.size(); }
  bool contains(Vertex goal) const { return by_goal_.count(goal) > 0; }
  size_t bytes() const;  // tables' distance arrays and open queues

 private:
  const Graph& g_;
  size_t max_tables_;
  uint64_t tick_ = 0;
  std::vector<std::unique_ptr<Table>> tables_;
  std::vector<std::unique_ptr<Table>> spare_;  // dropped tables, reused by table()
  std::unordered_map<Vertex, Table*> by_goal_;
  std::vector<uint8_t> extra_;  // set_arc_costs
  int max_extra_ = 0;
  bool met(const Table& t, Vertex from) const;
  Vertex unmet(const Table& t, Vertex from) const;  // first of from + neighbours undiscovered, or -1
  bool grow_chunk(Table& t, Vertex from);  // one chunk towards from; false: met
  void note_miss(Table& t, Vertex v);
  Deadline deadline_ = Deadline::max();
  bool expired_ = false;  // a query saw the clock past deadline_
  Counters counters_;
  std::vector<std::pair<Vertex, Vertex>> missed_;  // (goal, queried vertex) of estimated queries
  std::vector<std::pair<Table*, Vertex>> wanted_;  // prefetch queue (pinned); [wanted_head_, end) not yet met
  size_t wanted_head_ = 0;
};

}  // namespace planner
