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
#include <chrono>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "planner/graph.hpp"

namespace planner {

class RotationDist {
 public:
  static constexpr uint16_t kInf = 0xFFFF;  // not (yet) reached / unreachable
  static constexpr uint16_t kFar = 0xFFFE;  // saturation: every distance >= kFar reads kFar

  // Needs a grid graph (std::invalid_argument otherwise).
  explicit RotationDist(const Graph& g, size_t max_tables = 0);

  // The cell ahead of v facing o, or -1 (wall, obstacle, off the map).
  Vertex ahead(Vertex v, int o) const { return ahead_[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)]; }

  struct Table {
    std::vector<uint16_t> dist;   // state v * 4 + o
    std::vector<int32_t> queue;   // BFS order of states; [head, end) is open
    size_t head = 0;
    Vertex goal;
    int pins = 0;
    uint64_t used = 0;
    bool done() const { return head >= queue.size(); }
  };

  Table* table(Vertex goal);  // created on first use (unpinned)
  void pin(Table* t) { ++t->pins, t->used = ++tick_; }
  void unpin(Table* t) { --t->pins; }
  void trim();  // drops unpinned tables, least recently used first, down to the cap

  // h(v, o) in t; kInf when the goal cannot be reached from (v, o).
  uint16_t get(Table* t, Vertex v, int o) const
  {
    const uint16_t d = t->dist[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)];
    return d != kInf || t->done() ? d : grow_until(t, v * 4 + o);
  }

  // Replaces the prefetch queue with `goals` (most urgent first; pinned until the next call).
  void prefetch(const std::vector<Vertex>& goals);
  // Grows the queued tables to completion, in order, until the deadline (checked every 256
  // states). Returns whether work remains.
  bool precompute(std::chrono::steady_clock::time_point deadline);
  size_t pending() const { return wanted_.size() - wanted_head_; }

  const Graph& graph() const { return g_; }
  size_t num_tables() const { return tables_.size(); }
  size_t max_tables() const { return max_tables_; }
  void set_max_tables(size_t n) { max_tables_ = n; }
  size_t bytes() const;

 private:
  uint16_t grow_until(Table* t, int32_t state) const;
  void grow(Table* t, int32_t state, size_t pops) const;  // until `state` (-1: none) is reached or `pops` states

  const Graph& g_;
  size_t max_tables_;
  uint64_t tick_ = 0;
  std::vector<Vertex> ahead_;  // v * 4 + o -> neighbour or -1
  std::unordered_map<Vertex, std::unique_ptr<Table>> tables_;
  std::vector<Table*> wanted_;  // prefetch queue (pinned); [wanted_head_, end) not yet complete
  size_t wanted_head_ = 0;
};

}  // namespace planner
