#pragma once
// RotationDist: exact distances to a goal cell over (cell, heading) states under the
// rotation action model (LoRR's MAPF_T): each step a robot moves forward one cell into the
// cell it faces, turns 90 degrees clockwise or counter-clockwise in place, or waits.
// h(v, o) = the fewest such steps from cell v facing o to stand on the goal cell (any
// heading). Headings: 0 east (x + 1), 1 south (y + 1), 2 west, 3 north; clockwise = +1.
//
// Why its own tables (not a cell table plus the turns to face the next shortest-path
// step): that estimate is not exact; a longer cell path with fewer turns can be shorter
// in steps (tested against brute force: rotation_dist_test). A table is a backward BFS
// from the goal's four states: the predecessors of (v, o) are (v, o - 1) (turned
// clockwise), (v, o + 1) (counter-clockwise) and (v - dir(o), o) (moved forward). Like
// DistCache's tables it is lazy and resumable (lacam3's DistTable): a query grows the BFS
// only until the queried state is discovered.
//
// Directed graphs (one-way aisles): a forward move needs the arc v -> v + dir(o), and the
// backward BFS takes (v - dir(o), o) as a predecessor only over the arc into v (heading.hpp
// cell_ahead / cell_behind), so a table is the distance along the arcs, kInf where they do
// not reach the goal. The rotation planners read every move from ahead(), hence move along
// arcs only (DirectedGraph.* in test_rotation_pibt). Like PIBT they are not complete, on
// any graph.
//
// Memory: 4 states per cell, uint16 distances (8 bytes per cell, twice a DistCache cell
// table's 4) plus the open BFS queue (4 bytes per state on it; compacted, freed when the
// BFS is done). Distances saturate at 65,534 steps (kFar): beyond that a table is no
// longer exact (no LoRR map comes near: WAREHOUSE's farthest pair is ~700 steps). Tables
// are keyed by goal cell and shared by every agent with that goal; holders pin them;
// unpinned tables are dropped least recently used first beyond `max_tables` (0 = no cap).
//
// Prefetch (as DistCache's): goals known before they are needed (an agent's next errand)
// are queued (pinned) and their tables grown to completion in a step's spare time, so that
// the step that sets them as goals does not pay their BFS (154 k states on LoRR's
// WAREHOUSE).
//
// Guidance (guidance.hpp; set_guidance): distances in its costs (a forward move from v
// facing o costs forward_cost(v, o), a quarter turn turn_cost()) instead of steps. The
// backward search is then Dijkstra on a bucket (Dial) queue, one bucket per cost value
// (costs are small integers), lazy and resumable like the BFS: a state's distance is exact
// once the queue's level reached it (Table::settled). Without guidance (uniform costs) the
// plain BFS runs, as before.
//
// Move costs (Graph::set_move_costs: a slow lane's cells): a forward move into cell c costs
// its guidance cost plus (move_cost(c) - 1) x the cheapest forward cost (the extra steps it
// takes, priced as a step), capped at Guidance::kMaxCost; turns keep their cost. Folded
// once into the costs this class measures in (guidance(), forward_cost()), so every reader
// -- pibt-rot's ranking, epibt's operation costs, traffic flow, wppl's tables -- sees a
// slow aisle as costlier and routes round it when the detour is cheaper. On a weighted
// graph without guidance the tables are Dijkstra too. set_move_costs(false) switches the
// fold off (the distances of the uniform graph, as before costs existed).
//
// Deadline (as DistCache's; set_deadline, none by default): past it a query for a state
// its table has not settled does not grow the table but answers a lower bound, max(the
// search's level + 1, Manhattan distance x the cheapest forward cost + the fewest quarter
// turns x the turn cost), and queues the table (pinned) for precompute(), which grows
// such late tables first (and drops unfinished those nobody else holds any more). So a
// planning step never runs a search past its deadline; the tables catch up in later
// steps' spare time. Exact where settled or complete. A guided table's open queue costs
// 4 bytes per queued entry (stale ones included) until it is complete.
#include <chrono>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "planner/graph.hpp"
#include "planner/heading.hpp"
#include "planner/rotation/guidance.hpp"

namespace planner {

class RotationDist {
 public:
  static constexpr uint16_t kInf = 0xFFFF;  // not (yet) reached / unreachable
  static constexpr uint16_t kFar = 0xFFFE;  // saturation: every distance >= kFar reads kFar
  using Deadline = std::chrono::steady_clock::time_point;

  // Needs a grid graph (std::invalid_argument otherwise).
  explicit RotationDist(const Graph& g, size_t max_tables = 0);

  // The cell ahead of v facing o, or -1 (wall, obstacle, off the map, a one-way arc the
  // other way: heading.hpp cell_ahead).
  Vertex ahead(Vertex v, int o) const { return ahead_[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)]; }
  // The cell from which a forward move facing o enters v, or -1 (cell_behind).
  Vertex behind(Vertex v, int o) const { return behind_[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)]; }

  // Drops every table (the holders' Table pointers dangle: take them anew) and measures
  // distances in `gd`'s costs (plus the graph's move costs, above) from now on (uniform:
  // steps, by BFS). gd.forward must be empty or 4 per cell (std::invalid_argument otherwise).
  void set_guidance(Guidance gd);
  // Whether forward moves cost the graph's move costs (default true; false: as if all 1).
  // Drops every table, as set_guidance().
  void set_move_costs(bool on);
  bool move_costs() const { return costs_on_; }
  // The costs distances are measured in: the guidance with the move costs folded in.
  const Guidance& guidance() const { return guid_; }
  bool weighted() const { return weighted_; }
  uint16_t forward_cost(Vertex v, int o) const { return guid_.forward_cost(v, o); }
  uint16_t turn_cost() const { return guid_.turn; }

  struct Table {
    std::vector<uint16_t> dist;   // state v * 4 + o
    std::vector<int32_t> queue;   // BFS: order of states, [head, end) open; Dijkstra: unused
    size_t head = 0;
    std::vector<std::vector<int32_t>> buckets;  // Dijkstra: bucket d % size holds states queued at d
    size_t open = 0;              // Dijkstra: states in the buckets (stale ones too)
    uint32_t level = 0;           // Dijkstra: the bucket being popped; every d <= level is exact
    uint16_t settled = 0;         // dist[s] <= settled: exact (BFS: kFar, every discovered state)
    bool late = false;            // queued by a query past the deadline
    Vertex goal;
    int pins = 0;
    uint64_t used = 0;
    bool done() const { return buckets.empty() ? head >= queue.size() : open == 0; }
  };

  Table* table(Vertex goal);  // created on first use (unpinned)
  void pin(Table* t) { ++t->pins, t->used = ++tick_; }
  void unpin(Table* t) { --t->pins; }
  void trim();  // drops unpinned tables, least recently used first, down to the cap

  // h(v, o) in t; kInf when the goal cannot be reached from (v, o). Past the deadline a
  // lower bound where t has not settled (v, o) yet (see above).
  uint16_t get(Table* t, Vertex v, int o) const
  {
    const uint16_t d = t->dist[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)];
    return d <= t->settled || t->done() ? d : grow_until(t, v * 4 + o);
  }
  // The lower bound a query past the deadline answers for an unsettled state.
  uint16_t lower_bound(const Table* t, Vertex v, int o) const;

  // Queries past `d` answer lower bounds (Deadline::max(): none, every query exact).
  void set_deadline(Deadline d) { deadline_ = d, expired_ = false; }
  Deadline deadline() const { return deadline_; }
  uint64_t bounded_answers() const { return bounded_answers_; }  // lower bounds answered so far

  // Replaces the prefetch queue with `goals` (most urgent first; pinned until the next call).
  void prefetch(const std::vector<Vertex>& goals);
  // Grows the late tables that someone still holds, then the queued ones, to completion, in
  // order, until the deadline (checked every 256 states). Returns whether work remains.
  bool precompute(std::chrono::steady_clock::time_point deadline);
  size_t pending() const { return late_.size() + wanted_.size() - wanted_head_; }

  const Graph& graph() const { return g_; }
  size_t num_tables() const { return tables_.size(); }
  size_t max_tables() const { return max_tables_; }
  void set_max_tables(size_t n) { max_tables_ = n; }
  size_t bytes() const;

 private:
  uint16_t grow_until(Table* t, int32_t state) const;
  // Until `state` (-1: none) is settled or `pops` states were popped.
  void grow(Table* t, int32_t state, size_t pops) const;
  void grow_bfs(Table* t, int32_t state, size_t pops) const;
  void grow_dijkstra(Table* t, int32_t state, size_t pops) const;

  const Graph& g_;
  size_t max_tables_;
  uint64_t tick_ = 0;
  std::vector<Vertex> ahead_;   // v * 4 + o -> neighbour or -1
  std::vector<Vertex> behind_;  // v * 4 + o -> the cell a forward move facing o enters v from, or -1
  Guidance given_;  // set_guidance()'s, before the move costs
  Guidance guid_;   // given_ with the move costs folded in: what the tables measure
  bool costs_on_ = true;
  bool weighted_ = false;
  uint16_t min_forward_ = 1;
  std::unordered_map<Vertex, std::unique_ptr<Table>> tables_;
  std::vector<Table*> wanted_;  // prefetch queue (pinned); [wanted_head_, end) not yet complete
  size_t wanted_head_ = 0;
  Deadline deadline_ = Deadline::max();
  mutable bool expired_ = false;        // a query saw the clock past deadline_
  mutable std::vector<Table*> late_;    // tables queries past the deadline met (pinned)
  mutable uint64_t bounded_answers_ = 0;
};

}  // namespace planner
