#pragma once
// Scatter: space-utilisation optimisation (SUO; Han & Yu, ICRA-22), as used by Engineering
// LaCAM* (Okumura, AAMAS-24; lacam3's scatter.cpp). Every agent gets a single-agent path
// from its start to its goal that avoids the others' paths where it can at a small extra
// cost: A* over vertices (no waits, each vertex at most once) whose cost is first the
// number of collisions with the paths of all other agents (vertex, swap, and standing on
// somebody's goal after they arrived, at the step they would happen), then length, bounded
// by distance + `margin`. Passes over all agents in random order repeat while the total
// collision count drops (at least two). PIBT then prefers an agent's scatter successor of
// its current vertex among its candidates (pibt.hpp), which spreads agents over the map
// instead of sending all of them along the same shortest corridors.
//
// Real time: SUO for hundreds of agents takes longer than one 1 ms iteration, so it is
// resumable. step() continues where the last call stopped -- inside an agent's A* -- and
// returns at its deadline (checked every 64 A* pops) or after `max_work` units (A* pops x 4
// and path cells: what a budget in expansions charges). Guidance (next()) is published
// after each complete pass; before the first one it is empty.
#include <cstdint>
#include <vector>

#include "planner/budget.hpp"
#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"
#include "planner/rng.hpp"

namespace planner {

class Scatter {
 public:
  Scatter(const Graph& g, DistTable& dist) : g_(g), dist_(dist) {}

  // Starts SUO from `starts` towards the goals `dist` was set to (forgets everything).
  // max_passes > 0 stops after that many passes (0: lacam3's rule alone).
  void reset(const Config& starts, int margin, uint64_t seed, int max_passes = 0);
  void clear();  // no guidance, nothing to do
  // Builds what reset() would build on the first call (the per-vertex occupancy lists and the
  // A*'s parents, O(|V|) on fresh memory) in slices of kPrepareChunk vertices until `deadline`;
  // true once built. The first reset() of a timed run did it in one step: 1.1 ms at
  // warehouse-20-40-10-2-2 N = 1000 (a 1.5 ms iteration at a 1 ms cutoff). Optional: reset()
  // builds whatever is missing.
  bool prepare(Clock::time_point deadline);
  bool prepared() const;
  static constexpr size_t kPrepareChunk = 1024;
  // Open list of the A*: a bucket queue (default; O(1) push, measured in
  // docs/rt_lacam_star.md "Faster SUO") or a binary heap (the earlier code). Same order up
  // to ties between nodes with equal (collisions, f, g), so the paths may differ. Takes
  // effect at the next reset().
  void set_bucket_queue(bool on) { bucket_next_ = on; }
  // Live first pass (LacamOptions::scatter_live): each agent's path guides PIBT (next()) as
  // soon as its A* of the first pass ends, not only once the whole pass is published; the
  // agents not planned yet keep PIBT's distances. Later passes publish whole, as before.
  void set_live(bool on) { live_ = on; }
  bool live() const { return live_; }

  // Works until done, `deadline`, or about `max_work` units; true once done. With
  // `end_passes` false a step stops once a pass is complete and leaves its publication (O(the
  // paths' cells)) to publish(), which resumes at its own deadline (RT-LaCAM*'s timed runs).
  bool step(Clock::time_point deadline, uint64_t max_work = UINT64_MAX, bool end_passes = true);
  bool pass_complete() const { return pos_ == n_ && !done_; }  // publish() is due
  // Publishes the complete pass (when it has fewer collisions) until done or `deadline`
  // (checked every 16 agents); true once the pass has ended and the next one began (or SUO is
  // done). end_pass(): all at once.
  bool publish(Clock::time_point deadline);
  void end_pass();
  bool done() const { return done_; }
  bool ready() const { return !next_.empty(); }  // a complete pass has been published (live: one path)
  uint64_t work() const { return work_; }         // of the last step()
  int passes() const { return passes_; }
  int planned() const { return pos_; }  // agents done in the running pass
  int64_t collisions() const { return published_collisions_; }  // of the published pass

  // The vertex after v on agent i's published path, or -1 (v not on it, or its end).
  Vertex next(int i, Vertex v) const;
  const std::vector<Vertex>& path(int i) const { return published_[i]; }
  int num_agents() const { return n_; }
  // How often the per-vertex occupancy lists were built (tests: once; later resets empty the
  // cells the paths used instead, O(their length) against O(|V| x T)).
  long occupancy_builds() const { return occupancy_builds_; }

 private:
  long occupancy_builds_ = 0;
  bool live_ = false;
  void show(int i);  // live: agent i's path of the first pass guides at once
  struct Node {
    uint64_t key;  // (collisions, f, len_max_ - g), packed by key()
    Vertex v, parent;
  };
  uint64_t key(int64_t coll, int32_t f, int32_t g) const;
  size_t level(const Node& x) const;  // bucket of x: collisions x (margin + 1) + f - f0_
  void push(const Node& x);
  bool open_empty();  // (moves the bucket cursor past empty levels)
  Node pop();
  // Collisions of moving from u (at time t) to w (at t + 1) with the enrolled paths.
  int32_t collision_cost(Vertex u, Vertex w, int32_t t) const;
  void enroll(int i);
  void withdraw(int i);
  void begin_agent();
  bool run_astar(Clock::time_point deadline, uint64_t max_work);  // true when the agent is done

  const Graph& g_;
  DistTable& dist_;
  int n_ = 0, margin_ = 0, max_passes_ = 0;
  Rng rng_{0};
  Config starts_;
  std::vector<std::vector<Vertex>> paths_;      // being improved
  std::vector<std::vector<Vertex>> published_;  // of the last complete pass
  std::vector<std::vector<std::pair<Vertex, Vertex>>> next_;  // per agent, sorted (v, successor)
  // A publication in progress: agents [0, staged_) copied into the staging pair.
  std::vector<std::vector<Vertex>> staged_paths_;
  std::vector<std::vector<std::pair<Vertex, Vertex>>> staged_next_;
  int staged_ = 0;
  // body_[v][t]: head in cells_ of the list of agents at v at time t (-1: none); last_[v]:
  // arrival times of paths ending at v. A list head is 4 bytes, trivially filled: growing
  // body_[v] to a late step t costs a fill, not t vector constructions (enroll of one long
  // path took up to 0.4 ms at N = 1000 with a std::vector per step).
  struct Cell {
    int32_t agent, next;
  };
  std::vector<std::vector<int32_t>> body_;
  std::vector<Cell> cells_;
  int32_t free_cell_ = -1;
  int32_t count(int32_t head) const;
  void occupy(Vertex v, int32_t t, int i);
  void vacate(Vertex v, int32_t t, int i);
  std::vector<std::vector<int32_t>> last_;
  int64_t collisions_ = 0, pass_start_collisions_ = 0, published_collisions_ = 0;
  std::vector<int32_t> order_;
  int pos_ = 0, passes_ = 0;
  bool done_ = true, in_astar_ = false;
  // A* of the current agent (resumable).
  bool bucket_ = true, bucket_next_ = true;
  std::vector<Node> open_;                   // heap
  std::vector<std::vector<Node>> buckets_;  // bucket queue: [cur_, top_) may be non-empty
  size_t cur_ = 0, top_ = 0;
  static constexpr size_t kMaxLevels = size_t{1} << 20;  // higher levels share the last one
  bool level_sorted_ = false;
  int32_t f0_ = 0;  // f of the start (the lowest f)
  std::vector<Vertex> parent_;  // -2: not closed
  std::vector<Vertex> closed_;
  int32_t cost_ub_ = 0;
  int len_bits_ = 1;
  uint64_t len_max_ = 1, coll_max_ = 1;  // collisions saturate there (>= 2^22: never in practice)
  uint64_t work_ = 0;
};

}  // namespace planner
