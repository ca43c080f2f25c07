#pragma once
// LocalGuidance: local guidance for configuration-based MAPF (LG-LaCAM; Arita & Okumura,
// AAAI-26, "Local Guidance for Configuration-Based Multi-Agent Pathfinding"). Before PIBT
// makes a successor of a configuration Q, each agent, in PIBT's priority order, gets a short
// space-time path from Q[i] over a window of w steps (windowed decoupled planning); PIBT then
// tries that path's first step first (pibt.hpp). The path is found by A* over (vertex, time)
// whose cost is, lexicographically,
//   1. collisions: with the windowed paths of the agents planned before it (vertex and swap,
//      at the step they would happen) and with the current vertices of those not planned yet
//      (at t = 1: they may stay);
//   2. the steps spent off its goal (an agent staying on its goal pays nothing: the loss)
//      plus its distance to the goal at the window's end (h, consistent, so the first path
//      to reach t = w popped is the best).
// So an agent yields or steps aside for the higher-priority agents' next moves instead of
// running into them and waiting, which is where PIBT's greedy one-step preferences lose most
// (the paper: up to half the cost of LaCAM's solutions). Unlike SUO (scatter.hpp: time-free,
// once per instance) these cues are space-time and made again for every configuration.
//
// Cost: one A* per agent of at most kMaxNodes nodes (about (w + 1) x 5 in free space), so a
// generation costs O(N x w x degree) more than PIBT's O(N). plan() does one agent, so that
// Pibt's resumable generation can stop between two agents at a deadline.
#include <cstdint>
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"

namespace planner {

class LocalGuidance {
 public:
  LocalGuidance(const Graph& g, DistTable& d) : g_(g), d_(d) {}

  // The window w (>= 1); sizes the (w + 1) x |V| tables on the next begin().
  void set_window(int w) { w_ = w < 1 ? 1 : w; }
  int window() const { return w_; }
  // Whether the current vertices of the agents not planned yet count as collisions at t = 1.
  void set_count_unplanned(bool on) { unplanned_ = on; }
  // 0: collisions first, then cost (above); k > 0: one cost, a collision worth k steps (a
  // detour longer than that is not taken to avoid it).
  void set_collision_weight(int k) { weight_ = k < 0 ? 0 : k; }
  // An agent on its goal stays there in its path (no A*): it would otherwise step off its
  // goal for any higher-priority path through it in the window, paying the standard SOC
  // for a collision PIBT may never have (it pushes it only when somebody really comes).
  void set_rest_on_goal(bool on) { rest_ = on; }

  // A new round from configuration `from` of n agents towards `goals`: forgets the paths of
  // the last round (O(N x w), no O(V) clearing). `from` and `goals` must stay valid.
  void begin(const Vertex* from, int n, const Vertex* goals);
  // Agent i's windowed path around the agents planned so far in this round.
  void plan(int32_t i);
  bool planned(int32_t i) const { return stamp_of_[i] == round_; }
  // The first step of agent i's path in this round (-1 while it is not planned).
  Vertex next(int32_t i) const { return planned(i) ? paths_[static_cast<size_t>(i) * (w_ + 1) + 1] : -1; }
  // Agent i's path, w + 1 vertices from t = 0 (valid while planned(i)).
  const Vertex* path(int32_t i) const { return paths_.data() + static_cast<size_t>(i) * (w_ + 1); }
  uint64_t nodes() const { return nodes_total_; }  // A* nodes pushed, over all rounds (tests)

  static constexpr int kMaxNodes = 4096;  // an A* that reaches it keeps its deepest best node

 private:
  struct Node {
    Vertex v;
    int32_t t, parent, g, coll;
  };
  size_t at(int t, Vertex v) const { return static_cast<size_t>(t) * V_ + static_cast<size_t>(v); }

  const Graph& g_;
  DistTable& d_;
  bool unplanned_ = false;
  int weight_ = 0;
  bool rest_ = false;
  int w_ = 5, tw_ = 0;  // window; the window the tables are sized for
  size_t V_ = 0;
  int n_ = 0;
  const Vertex* from_ = nullptr;
  const Vertex* goals_ = nullptr;
  std::vector<Vertex> from_copy_;  // the last round's start (its t = 0 marks to clear)
  std::vector<uint16_t> cnt_;      // (t, v) -> planned paths there at t (t >= 1)
  std::vector<int32_t> who_;       // (t, v) -> an agent there at t: all at t = 0, planned ones after
  std::vector<uint32_t> closed_;   // (t, v) -> A* call that closed it
  uint32_t call_ = 0;
  std::vector<Vertex> paths_;      // agent * (w + 1) + t
  std::vector<uint32_t> stamp_of_; // agent -> round it was planned in
  uint32_t round_ = 0;
  std::vector<int32_t> planned_list_;  // agents planned in this round (their marks to clear)
  std::vector<Node> nodes_;
  std::vector<std::pair<uint64_t, int32_t>> open_;  // min-heap by key
  uint64_t nodes_total_ = 0;
};

}  // namespace planner
