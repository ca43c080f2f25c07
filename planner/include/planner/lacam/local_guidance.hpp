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
// generation costs O(N x w x degree) more than PIBT's O(N) (4x an unguided 0.01 ms iteration at
// w = 5, docs/rt_lacam_star.md session 37). plan() does one agent, so that Pibt's resumable
// generation can stop between two agents at a deadline.
//
// Amortized (set_refresh(R) > 0, session 38): a windowed path stays useful for about w steps,
// so a round keeps the last round's paths instead of forgetting them. begin() shifts each
// agent's path by the step the configuration advanced (0 when the same configuration is
// expanded again, 1 when it is the last round's successor), drops a path that no longer starts
// at the agent's vertex (PIBT did not follow it, or the search jumped elsewhere), and extends a
// kept one by one greedy step at the window's end. Pibt's guide phase then walks the agents in
// priority order: a kept path goes back into the space-time table at its agent's turn (hold),
// so that an agent planned again meets only the paths before it, as in LG-LaCAM; an A* runs
// for an agent without a path, with a kept path that meets an earlier one (repair) or one R
// rounds old. With set_budget(k) a round pushes at most about k x N A* nodes (a full round
// pushes ~25-30 x N at w = 5); the agents past it keep their old path or go unguided. So the
// work per generation is bounded, whatever the congestion, and counted in nodes (the same on
// every machine: the plan does not depend on the clock).
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
  // Amortized rounds (above): a kept path is planned again once it is R rounds old; 0 = off
  // (every round plans every agent from scratch, LG-LaCAM's rule).
  void set_refresh(int r) { refresh_ = r < 0 ? 0 : r; }
  int refresh() const { return refresh_; }
  // At most about k x N A* nodes pushed per round (the A* that crosses it ends); 0 = no cap.
  void set_budget(double k) { budget_ = k < 0 ? 0 : k; }

  // Sizes the (w + 1) x |V| tables now (begin() does it otherwise, inside the first guided
  // generation: 2.7 ms of one 0.1 ms iteration on warehouse-20-40-10-2-2, page faults under
  // load); true if it did. Lacam calls it when it is built.
  bool prepare();
  // A new round from configuration `from` of n agents towards `goals`: forgets the paths of
  // the last round (O(N x w), no O(V) clearing). `from` and `goals` must stay valid.
  void begin(const Vertex* from, int n, const Vertex* goals);
  // Agent i's windowed path around the agents planned so far in this round.
  void plan(int32_t i);
  bool planned(int32_t i) const { return stamp_of_[i] == round_; }
  // Amortized: agent i's kept path into the tables, at its turn in priority order (the agents
  // planned after it meet it); nothing for an agent without a path or in plain rounds.
  void hold(int32_t i);
  // Amortized: agent i's kept path meets a path in the tables (vertex or swap): planned again
  // when repair is on (set_repair).
  bool blocked(int32_t i) const;
  void set_repair(bool on) { repair_ = on; }
  bool repair() const { return repair_; }
  // Amortized: agent i has a kept path that is R rounds old (planned again while the round's
  // budget lasts: over()).
  bool stale(int32_t i) const { return planned(i) && refresh_ > 0 && age_[i] >= refresh_; }
  bool over() const { return budget_ > 0 && static_cast<double>(round_nodes_) >= budget_ * n_; }
  uint64_t kept() const { return kept_total_; }  // paths kept across a round, over all rounds (tests)
  // Congestion at the start: the share of the first N paths planned (N agents) that could not
  // run at full speed (they wait, detour or keep a collision); -1 until N paths are planned.
  // Lacam's lg_gate reads it (lacam.hpp).
  double first_conflicted() const { return first_share_; }
  void forget_first() { first_share_ = -1, first_planned_ = first_hit_ = 0; }  // a new instance
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
  bool in_tables(int32_t j) const { return refresh_ > 0 ? marked_[j] != 0 : planned(j); }
  void mark(int32_t i);    // agent i's path (t >= 1) into the tables
  void unmark(int32_t i);  // and out
  void keep(const Vertex* from, int n);  // begin()'s amortized part

  const Graph& g_;
  DistTable& d_;
  bool unplanned_ = false;
  int weight_ = 0;
  bool rest_ = false;
  int refresh_ = 0;
  bool repair_ = false;
  double budget_ = 0;
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
  std::vector<Vertex> goals_copy_; // amortized: the goals the kept paths lead to
  std::vector<uint8_t> marked_;    // amortized: agent -> its path is in the tables
  std::vector<uint16_t> age_;      // amortized: agent -> rounds since its path was planned
  uint64_t round_nodes_ = 0, kept_total_ = 0;
  int first_planned_ = 0, first_hit_ = 0;
  double first_share_ = -1;
  std::vector<Node> nodes_;
  std::vector<std::pair<uint64_t, int32_t>> open_;  // min-heap by key
  uint64_t nodes_total_ = 0;
};

}  // namespace planner
