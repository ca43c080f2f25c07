#pragma once
// Pibt: Priority Inheritance with Backtracking (Okumura et al., AIJ 2022) as LaCAM's
// configuration generator. generate() makes one successor configuration in which the
// agents fixed by a LaCAM Constraint chain take their fixed vertices and all others are
// planned by PIBT in priority order.
//
// With `swap` on (default), PIBT uses the swap operation of LaCAM* (Okumura, IJCAI-23):
// when two agents must pass each other in a corridor, the leading agent reverses its
// preferences and pulls the other into its old vertex, which vanilla PIBT cannot do. It
// is what lets LaCAM (and so RT-LaCAM) solve dense warehouse aisles. On a directed graph
// (one-way arcs) a partner is pulled only over an arc into the vacated vertex; every other
// move PIBT makes is to an out-neighbour, so its configurations are legal there too.
#include <cstdint>
#include <vector>

#include "planner/action_preference.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"
#include "planner/lacam/hnode.hpp"
#include "planner/lacam/immobile.hpp"
#include "planner/rng.hpp"
#include "planner/lacam/scatter.hpp"

namespace planner {

class Pibt {
 public:
  Pibt(const Graph& g, DistTable& d, bool swap = true);

  // Goals are needed by the swap operation (an agent parked on its goal in a dead end
  // does not need to move) and are passed on to the preference. Sizes the agent arrays.
  void set_goals(const Config& goals);
  void set_preference(ActionPreference* pref) { pref_ = pref; }
  // Immobile agents (immobile.hpp; per agent, 1 = immobile, empty = none): never moved,
  // never pushed (their only candidate is staying), never pulled by a swap. Kept across
  // set_goals().
  void set_immobile(const std::vector<uint8_t>& immobile) { immobile_ = immobile; }
  bool swap() const { return swap_; }
  // SUO guidance (scatter.hpp; null = none): an agent's scatter successor of its current
  // vertex comes first among its candidates (lacam3's pibt.cpp).
  void set_scatter(const Scatter* s) { scatter_ = s; }

  // Writes a successor of `from` into `to`. Agents are planned in `order` (highest
  // priority first); `c` (may be null) fixes some agents. Returns false when the fixed
  // agents collide or PIBT cannot place a top-level agent.
  bool generate(const Vertex* from, const int32_t* order, const Constraint* c, Vertex* to, Rng& rng);

 private:
  bool plan(int32_t i, Rng& rng);  // funcPIBT
  int32_t swap_partner(int32_t i) const;
  bool swap_required(int32_t pusher, int32_t puller, Vertex v_pusher, Vertex v_puller) const;
  bool swap_possible(Vertex v_pusher, Vertex v_puller) const;
  bool pull_impossible(Vertex u, Vertex v_pusher) const;
  bool immobile(int32_t i) const { return !immobile_.empty() && immobile_[i]; }
  // Agent i's distance from u to its goal: around the immobile agents when its goal can be
  // reached that way (DetourTable), else the plain one.
  float distance(int32_t i, Vertex u);

  const Graph& g_;
  DistTable& d_;
  bool swap_;
  ActionPreference* pref_ = nullptr;
  const Scatter* scatter_ = nullptr;
  Config goals_;
  int n_ = 0;
  int stride_;                      // candidates per agent: max degree + 1
  std::vector<int32_t> occ_now_;    // vertex -> agent there now, or -1
  std::vector<int32_t> occ_next_;   // vertex -> agent reserved there next, or -1
  std::vector<Vertex> now_;         // agent -> current vertex
  std::vector<Vertex> next_;        // agent -> next vertex, or -1 while unplanned
  std::vector<Vertex> cand_;        // agent * stride_ + k
  std::vector<float> key_;          // scratch for sorting candidates
  std::vector<uint8_t> immobile_;   // agent -> 1 if immobile (empty: none)
  DetourTable detour_;              // distances around the immobile agents
  std::vector<uint32_t> cut_off_stamp_;  // agent -> generate() call cut_off_ was set in
  std::vector<uint8_t> cut_off_;         // agent -> no path around the immobile agents
  uint32_t generation_ = 0;
};

}  // namespace planner
