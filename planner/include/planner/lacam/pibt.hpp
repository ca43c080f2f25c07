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
//
// Resumable generation: one call plans all N agents (0.2-1 ms at N = 1000), more than a
// 0.1 ms iteration. start() does the O(N) set-up and fixes the constraint's agents; resume()
// plans the top-level agents in priority order and may stop at a deadline between two of
// them (one top-level plan(), with its priority-inheritance chain, is the smallest unit);
// the next resume() goes on where it stopped. The random draws are the same, in the same
// order, as in one generate() call, so the successor is the same. set_goals() and
// set_immobile() cancel a paused generation (pending() turns false).
#include <cstdint>
#include <vector>

#include "planner/action_preference.hpp"
#include "planner/budget.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"
#include "planner/lacam/hnode.hpp"
#include "planner/lacam/immobile.hpp"
#include "planner/lacam/local_guidance.hpp"
#include "planner/rng.hpp"
#include "planner/lacam/scatter.hpp"
#include "planner/zones.hpp"

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
  void set_immobile(const std::vector<uint8_t>& immobile)
  {
    immobile_ = immobile;
    pending_ = false;  // a paused generation set up its detours for the old mask
  }
  // Foreign pockets (dead-end station stubs; the task layer labels them, tasks.urgency
  // pocket_cost): pocket[v] labels the cells of each dead end (-1 elsewhere); an agent moving
  // into a pocket other than its goal's, from outside it, pays `cost` on top of the move's
  // distance. Empty or 0: off.
  void set_pockets(std::vector<Vertex> pocket, float cost)
  {
    pocket_ = std::move(pocket);
    pocket_cost_ = cost;
  }
  // One-at-a-time zones (zones.hpp; null = none): a move into a zone that another agent
  // holds this step (it is in it now, or a move into it is planned already) is no candidate,
  // a swap never pulls a partner into one, and a constraint that breaks them fails the
  // generation. Takes effect at the next start(). Priority inheritance for a zone: an agent
  // that wants into a zone held by one standing in it, not planned yet, has it planned first
  // with a move out of the zone ranked first (else toward the nearest other way out), so the
  // zone is free the step after -- without it an agent parked on its goal in a zone blocks
  // the zone for good, and LaCAM alone took up to 2M expansions to get it out (16 agents on
  // the small SUMO warehouse, docs/closed_loop_bench.md).
  void set_zones(const Zones* zones) { zones_ = zones; }
  bool swap() const { return swap_; }
  // Tie-break among the moves toward the goal that are equally short (free_first): a vertex
  // nobody stands on now first (PIBT's occupancy tie-break, Okumura AIJ 2022 / pibt2), then
  // one whose agent can step on elsewhere, last one whose agent is parked on its goal or
  // wants this agent's vertex (head-on: pushing it sends it back). Sideways moves, staying
  // and moves away keep random ties: preferring free vertices there too made LaCAM's first
  // search on random-32-32-20 N = 400 take 800-2400 expansions instead of ~110
  // (docs/rt_lacam_star.md, session 36). Off: random ties everywhere (lacam3's PIBT). The
  // same random draws either way.
  void set_free_first(bool on) { free_first_ = on; }
  bool free_first() const { return free_first_; }
  // Highways (highways.hpp; null: off): candidates are ranked by `guide`'s distances (the
  // goals set on it by the owner) instead of the plain ones, and the swap operation decides
  // on them too (it simulates the pusher walking its ranked way); free_first's levels keep
  // the plain distances.
  void set_guide(DistTable* guide) { guide_ = guide; }
  // SUO guidance (scatter.hpp; null = none): an agent's scatter successor of its current
  // vertex comes first among its candidates (lacam3's pibt.cpp).
  void set_scatter(const Scatter* s) { scatter_ = s; }
  const Scatter* scatter() const { return scatter_; }
  // Local guidance (local_guidance.hpp; null = none): each generation first plans every
  // agent's windowed space-time path in priority order (a phase of resume(), stoppable
  // between two agents), and an agent's first step on it comes first among its candidates,
  // before its scatter successor. Takes effect at the next start().
  void set_local_guidance(LocalGuidance* lg) { lg_next_ = lg; }
  const LocalGuidance* local_guidance() const { return lg_next_; }

  // Writes a successor of `from` into `to`. Agents are planned in `order` (highest
  // priority first); `c` (may be null) fixes some agents. Returns false when the fixed
  // agents collide or PIBT cannot place a top-level agent.
  bool generate(const Vertex* from, const int32_t* order, const Constraint* c, Vertex* to, Rng& rng);

  // generate() in pieces: start() only records the call; resume() does its work -- undo the
  // last call's reservations, place the agents at `from`, fix the constraint's agents, with
  // local guidance plan every agent's windowed path, plan the others -- until the successor is made (done: it is result()), the fixed agents
  // collide or PIBT cannot place a top-level agent (failed), or `deadline` has passed
  // (paused). The clock is read every kSetupEvery agents while setting up, every
  // kCheckEvery top-level plan() calls after; each resume() does at least that much.
  // `from`, `order` and the constraints must stay valid until the generation ends.
  enum class Gen { done, failed, paused };
  void start(const Vertex* from, const int32_t* order, const Constraint* c);
  Gen resume(Rng& rng, Clock::time_point deadline = Clock::time_point::max());
  bool pending() const { return pending_; }  // started, and neither ended nor cancelled
  const Vertex* result() const { return next_.data(); }  // after resume() returned done
  uint64_t plans() const { return plans_; }  // top-level agents handled, over all calls (tests)
  static constexpr int kCheckEvery = 8;
  static constexpr int kGuideEvery = 2;  // windowed A* per clock reading (local guidance)
  static constexpr int kSetupEvery = 64;

 private:
  bool plan(int32_t i, Rng& rng);  // funcPIBT
  int32_t swap_partner(int32_t i) const;
  bool swap_required(int32_t pusher, int32_t puller, Vertex v_pusher, Vertex v_puller) const;
  bool swap_possible(Vertex v_pusher, Vertex v_puller) const;
  bool pull_impossible(Vertex u, Vertex v_pusher) const;
  bool immobile(int32_t i) const { return !immobile_.empty() && immobile_[i]; }
  // Zones (set_zones): may agent i move to u (no zone of u held by another), and take (or give
  // back) the zones it enters moving v -> u.
  bool zone_free(int32_t i, Vertex u) const
  {
    if (!zones_) return true;
    for (int z : zones_->of[u])
      if (zone_holder_[z] >= 0 && zone_holder_[z] != i) return false;
    return true;
  }
  void zone_take(int32_t i, Vertex v, Vertex u, bool take)
  {
    if (!zones_) return;
    for (int z : zones_->of[u])
      if (!zones_->in(v, z)) zone_holder_[z] = take ? i : -1;
  }
  // Agent i's distance from u to its goal: around the immobile agents when its goal can be
  // reached that way (DetourTable), else the plain one.
  float distance(int32_t i, Vertex u);
  // A move's cost beyond 1 (graph move costs: a slow lane's cell): ranking v -> u by
  // d(u) + cost(u) - 1 ranks by the time to the goal through u; staying keeps d(v). 0
  // without move costs, so the unit ranking is unchanged.
  float extra_cost(Vertex v, Vertex u) const { return u == v ? 0.0f : static_cast<float>(g_.move_cost(u) - 1); }
  float pocket_cost(int32_t i, Vertex v, Vertex u) const
  {
    if (pocket_cost_ <= 0.0f || pocket_.empty()) return 0.0f;
    const Vertex p = pocket_[u];
    return p >= 0 && p != pocket_[v] && p != pocket_[goals_[i]] ? pocket_cost_ : 0.0f;
  }

  const Graph& g_;
  DistTable& d_;
  DistTable* guide_ = nullptr;
  bool swap_;
  bool free_first_ = false;
  ActionPreference* pref_ = nullptr;
  const Scatter* scatter_ = nullptr;
  LocalGuidance* lg_ = nullptr;       // of the generation in progress
  LocalGuidance* lg_next_ = nullptr;  // set_local_guidance()
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
  std::vector<Vertex> pocket_;      // vertex -> its dead-end pocket, or -1 (set_pockets)
  float pocket_cost_ = 0.0f;
  const Zones* zones_ = nullptr;
  std::vector<int32_t> zone_holder_;  // zone -> the agent holding it this step, or -1
  std::vector<int32_t> evict_zone_;   // agent -> the zone it is asked to leave, or -1
  std::vector<int32_t> exit_dist_;    // zone vertex -> moves to a way out (evict())
  void evict(int32_t i, Vertex v, Vertex u, Rng& rng);
  DetourTable detour_;              // distances around the immobile agents
  std::vector<uint32_t> cut_off_stamp_;  // agent -> generate() call cut_off_ was set in
  std::vector<uint8_t> cut_off_;         // agent -> no path around the immobile agents
  uint32_t generation_ = 0;
  // The generation in progress (start() .. resume() done / failed) and its cursor.
  enum class Phase { undo, place, chain, guide, plan };
  const Vertex* from_ = nullptr;
  const int32_t* order_ = nullptr;
  const Constraint* chain_ = nullptr;
  Phase phase_ = Phase::plan;
  int k_ = 0;               // next agent (undo, place) or index into order_ (plan)
  bool pending_ = false;
  uint64_t plans_ = 0;
};

}  // namespace planner
