#pragma once
// Lacam: the lazy depth-first search over configurations of LaCAM (Okumura, AAAI-23).
//
// The search keeps an explicit DFS stack (Open) of HNodes. One expansion looks at the top
// node H: if its configuration satisfies the goal test the search is solved; if its
// low-level queue is exhausted H is popped; otherwise the next Constraint is taken from
// H's queue (adding its children, one per move of the next agent in H's order), PIBT
// generates a successor honouring it, and the successor -- new, or already explored --
// is pushed. Revisits thus re-push known nodes, whose next constraint forces a different
// successor: this is what makes LaCAM complete. It reports NoSolution only after every
// node's constraint tree is exhausted.
//
// LaCAM* refinement (LacamOptions::refine; Okumura, IJCAI-23, and lacam3's planner.cpp).
// Cost: one per agent per action, 0 for an agent that stays on its goal. Before the first
// solution nothing changes but the bookkeeping: each expansion records a neighbour link
// (both directions) and the tree, the expansions and the explored set are exactly LaCAM's.
// At the first solution every node gets g (cost of its tree path from the root) and h (sum
// of distances), and the search goes on instead of stopping: nodes with g >= g(goal) are
// popped, successors are pushed only when f = g + h < f(goal), every revisit adds a link and
// runs a Dijkstra-style relaxation from the revisiting node (a node whose g drops takes the
// relaxing node as its new parent, and the drop propagates), and with probability
// restart_rate a revisit pushes the root instead (LaCAM*'s random insertion of the start).
// goal_node()'s tree path is thus the best path known, and only gets cheaper. When Open
// empties the path is optimal (among paths through known configurations, which then are all
// that LaCAM* can reach) and, unless LNS still finds improvements, refining() turns false.
// LacamOptions::lns interleaves LnsRefiner steps (lns_refiner.hpp): an improved path's
// configurations are inserted as nodes/links and rewired like revisits.
//
// Rerooting with costs (sunk cost): the executed prefix is not counted, g is re-based at
// the new root. After reroot(c), c has g = 0, the old root hangs under c with g =
// cost(c, old root), and every other node keeps its parent; one walk over the tree from c
// sets g(y) = g(x) + (g_old(y) - g_old(x)) along every unchanged edge x -> y (exact, since g
// was exact before) and the one reversed edge's cost explicitly. O(nodes + links) per move,
// only once refining. Before the first solution reroot() stays O(1) and g is computed once,
// at the first solution, by the same walk with explicit edge costs.
//
// Memory: a link is 16 bytes and an expansion adds at most two, against a node's 12 bytes
// per agent; the whole search (nodes, configurations, constraints, links) is capped by
// refine_max_mb: past it, refinement stops and the best path so far is kept. The first
// solution's search is never capped (completeness).
//
// The same object serves full-horizon LaCAM (search to the end, then path()),
// RT-LaCAM (search a little, move to root's child toward the top, reroot(), continue)
// and naive RT-LaCAM (reset() every iteration).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "planner/action_preference.hpp"
#include "planner/lacam/arena.hpp"
#include "planner/budget.hpp"
#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/lacam/explored_table.hpp"
#include "planner/lacam/hnode.hpp"
#include "planner/lacam/lns_refiner.hpp"
#include "planner/lacam/pibt.hpp"
#include "planner/rng.hpp"
#include "planner/lacam/scatter.hpp"
#include "planner/lacam/step_cost.hpp"
#include "planner/search_types.hpp"

namespace planner {

struct LacamOptions {
  bool swap = true;    // PIBT swap operation (LaCAM*); off for paper-faithful vanilla runs
  uint64_t seed = 0;   // tie-breaks in PIBT and the shuffle of constraint children
  // Lifelong goal changes (set_goals) keep the agents' PIBT priorities instead of starting
  // again from distance / N. Measured: +10-30 % throughput on the LoRR random-32-32-20
  // instances, but half the throughput in a small warehouse whose stations are dead-end
  // stubs (long-waiting agents crowd the stubs); so it is a choice, not a rule.
  bool keep_priorities = true;
  // LaCAM* refinement after the first solution (see above). Off here, so that the library
  // default stays the paper's RT-LaCAM; the apps switch it on by default.
  bool refine = false;
  double restart_rate = 0.001;  // lacam3's RESTART_RATE
  size_t refine_max_mb = 512;   // refinement stops past this much search memory
  // With refine: every other refinement iteration is one LnsRefiner step on the best path
  // (lns_agents agents replanned); an improved path is inserted into the tree and rewired.
  bool lns = true;
  int lns_agents = 8;
  int lns_window = 256; // time steps replanned per LNS step (the occupancy table is window x |V|)
  LnsNeighbourhood lns_neighbourhood = LnsNeighbourhood::random;  // which agents a step replans
  // Engineering LaCAM* (Okumura, AAMAS-24) guidance, with refine, all in the refinement's own
  // budget (a third slot of the rotation LNS / LaCAM* / guide; the first solution's search is
  // untouched):
  //  - scatter: space-utilisation optimisation (scatter.hpp), resumable across iterations,
  //    from the configuration scatter_lead steps ahead on the best path; after
  //    scatter_dive_passes passes (and each later one) a guided dive from there (or from the
  //    root once the agents are past it). SUO takes every refinement iteration until the
  //    first dive, then a third; the first guided dive that does not beat the best path
  //    stops it. PIBT keeps preferring each agent's scatter successor in every later
  //    refinement expansion and dive.
  //  - dive: PIBT rollouts from the current root to the goals (LaCAM's first descent, now
  //    guided), inserted as nodes and links and rewired like an LNS path, so the goal's g
  //    drops when a rollout is cheaper. Up to 2 x the best path's length + 16 steps each.
  //  Measured in docs/rt_lacam_star.md ("Third pass: SUO"): scatter on in rtlacam-bench,
  //  dive and scatter_first off.
  bool scatter = false;
  int scatter_margin = 10;  // lacam3's SCATTER_MARGIN: extra length allowed per agent
  // SUO starts from the configuration this many steps ahead on the best path: the agents
  // move on while it is computed, and the guided dive starts there. Adapted once, after an
  // eighth of the first pass (lacam_guide.cpp), when SUO proves slower than that.
  int scatter_lead = 30;
  int scatter_dive_passes = 2;  // the first guided dive waits for this many passes (lacam3: >= 2)
  int scatter_max_passes = 0;  // 0: lacam3's rule (at least two, on while collisions drop)
  bool dive = false;
  // SUO before the first solution (lacam3's order; counts against the iterations' budget).
  // It changes PIBT and so the tree: the first solution is then not LaCAM's.
  bool scatter_first = false;
};

class Lacam {
 public:
  // `dist` must outlive the search; it is shared so that naive RT-LaCAM and goal changes
  // reuse BFS tables. `pref` (optional) orders PIBT's candidate moves.
  Lacam(const Graph& g, DistTable& dist, LacamOptions opt = {}, ActionPreference* pref = nullptr);

  // Drops the tree and starts a new search rooted at `start` towards `goals`. The root's
  // PIBT priorities are `priorities` when given (a lifelong epoch carries them over, so
  // agents that waited long keep winning conflicts), else distance / N. `order`, with
  // `priorities`, is the agents' order under them (or a near one) to sort from: the root's
  // order is the same, found in O(N) instead of a full sort at each epoch start.
  void reset(const Config& start, const Config& goals, GoalTest test = {}, const float* priorities = nullptr,
             const int32_t* order = nullptr);

  // Immobile agents (immobile.hpp; per agent, 1 = immobile, empty = none): PIBT keeps them
  // in place, their constraints only let them stay, and LNS refinement is off while any
  // is. Takes effect at the next reset(): a tree built without the mask has moves for them.
  void set_immobile(const std::vector<uint8_t>& immobile);

  Status expand();                   // one LaCAM (or, once solved, LaCAM*) iteration
  // Expands until solved (with refine: until refinement ends), exhausted or out of budget
  // (>= 1 expansion while there is anything to do before the first solution).
  // With a time budget, refinement keeps it: no refinement step starts unless its predicted
  // cost (step_cost.hpp, thread CPU time) fits what is left of the call less the next
  // reroot's; an LNS step's window is cut to fit, SUO, dives and the first solution's costing
  // (g, h of every node) are resumable and stop at the call's end. With Budget::reserve_ms,
  // LaCAM's expansions before the first solution are predicted the same way (after the
  // first of each call, which is always made). Against b.expansions an LNS step counts
  // as its work (cells and A* states visited) / N expansions, a LaCAM(*) expansion as one;
  // what a step overruns is paid off by the next calls (they refine less or not at all).
  // `until_solved`: return at the first solution instead of refining on.
  Status search(const Budget& b, bool until_solved = false);
  Status status() const { return status_; }
  bool refining() const { return refining_; }        // solved, refine on, Open not empty, under the cap
  bool refine_capped() const { return refine_capped_; }  // refinement stopped by refine_max_mb
  const Scatter& scatter() const { return scatter_; }
  uint64_t dives() const { return dives_; }           // completed dives, and those that lowered g(goal)
  uint64_t dive_wins() const { return dive_wins_; }
  size_t bytes_reserved() const;

  // LaCAM*'s edge cost: agents that move or leave/are off their goal (symmetric).
  int32_t edge_cost(const Vertex* a, const Vertex* b) const;
  // Once solved with refine: g of the tree path root -> h equals the sum of edge costs
  // along it, for every node (for tests; O(nodes * depth)).
  bool check_costs(std::string* why = nullptr) const;

  int num_agents() const { return n_; }
  const Config& goals() const { return goals_; }
  const HNode* root() const { return root_; }
  const HNode* top() const { return open_.empty() ? nullptr : open_.back(); }
  const HNode* goal_node() const { return goal_; }

  // Configurations along the tree from the root to `to`.
  std::vector<Config> path(const HNode* to) const;
  // The root's child on the tree path root -> target, or the root itself when target is
  // the root (or null).
  const HNode* next_toward(const HNode* target) const;
  // RT-LaCAM's reroot: `child` (a neighbour of the root: its tree child, or, after LaCAM*
  // rewired it, a former one) becomes the root, the old root hangs under it. Nothing else in
  // the tree, the explored table or the constraints changes; g is re-based (above).
  void reroot(const HNode* child);

  uint64_t expansions() const { return expansions_; }  // since construction, over all resets
  // CPU ms of the costliest expansion of the last search() with a reserve (Budget::reserve_ms).
  double max_expansion_ms() const { return max_unit_ms_; }
  // Predicted CPU ms of one expansion, and ms per (time step x agent) of an LNS window
  // (step_cost.hpp), for statistics and tests.
  const StepCost& expansion_cost() const { return expand_cost_; }
  const StepCost& lns_cost() const { return lns_cost_; }
  bool preparing() const { return preparing_; }  // refining, but g and h not yet computed for all
  // expansions() and explored() when the current search found its first solution
  uint64_t expansions_at_solution() const { return solved_expansions_; }
  size_t explored_at_solution() const { return solved_explored_; }
  size_t explored() const { return explored_.size(); }
  size_t open_size() const { return open_.size(); }

  // Tree invariants (for tests): the root has no parent, the parent pointers of every
  // explored node lead to the root without cycles. On failure, `why` says where.
  bool check_tree(std::string* why = nullptr) const;

 private:
  HNode* new_node(const Vertex* C, HNode* parent, uint64_t hash, const float* root_priorities = nullptr,
                  const int32_t* root_order = nullptr);
  bool is_goal(const HNode* h) const;
  // LaCAM* (lacam_star.cpp)
  void link(HNode* a, HNode* b);           // neighbour links both ways, no duplicates
  int32_t cost(HNode* from, Neighbor* e);  // lazily computed edge cost
  int32_t heuristic(const Vertex* C);
  void start_refining();                   // at the first solution: g, h for all (resumable)
  bool prepare_step();                     // the next nodes' h and link costs; true when done
  double room_ms() const;                  // wall ms left to the running call
  bool fits(double ms) const { return room_ms() >= ms; }
  Status refine_expand();
  void rewrite(HNode* a, HNode* b);        // Dijkstra-style relaxation from a new link
  void rebase(HNode* new_root, HNode* old_root, bool explicit_costs);
  void push_if_promising(HNode* h);
  void grow_lowlevel(HNode* H, const Constraint* L);
  bool lns_step(int window);                // one LnsRefiner step; an improved window goes to pending_
  bool insert_step();                       // inserts pending_ while it fits; true when done
  void guide_step();                        // scatter work, else a dive step (lacam_guide.cpp)
  bool scatter_step();                      // false once SUO is done (or off)
  void dive_step();
  void start_dive(HNode* from);
  int steps_ahead(const HNode* x) const;  // x's depth on the best path, -1 if not on it
  void start_scatter(int lead);
  HNode* step_to(HNode* from, const Vertex* C);  // known or new node after `from`, linked and rewired

  static constexpr int kMinLnsWindow = 4;  // shorter windows rarely leave room to improve

  const Graph& g_;
  DistTable& dist_;
  LacamOptions opt_;
  Pibt pibt_;
  Rng rng_;
  int n_ = 0;
  Config goals_;
  GoalTest goal_test_;

  Arena<HNode> nodes_;
  Arena<Constraint> constraints_;
  Arena<Vertex> configs_;
  Arena<int32_t> orders_;
  Arena<float> priorities_;
  Arena<Neighbor> links_;
  ExploredTable explored_;
  std::vector<HNode*> open_;
  std::vector<HNode*> all_;   // every explored node, by id
  HNode* root_ = nullptr;
  HNode* goal_ = nullptr;
  Status status_ = Status::NoSolution;
  uint64_t expansions_ = 0;
  double max_unit_ms_ = 0;  // max_expansion_ms()
  bool refining_ = false, refine_capped_ = false;
  LnsRefiner lns_;
  Scatter scatter_;
  bool scatter_started_ = false, first_dive_done_ = false;
  HNode* scatter_root_ = nullptr;  // the node whose configuration SUO started from
  int passes_dived_ = 0;           // SUO passes already followed by a dive
  bool scatter_probed_ = false;    // the lead was checked against SUO's speed
  bool guided_dive_ = false, scatter_stopped_ = false;  // a dive after a pass; one of them lost
  uint64_t reroots_ = 0, scatter_reroots0_ = 0;  // reroots, and their count when SUO started
  HNode* dive_ = nullptr;       // the running dive's last node (null: none)
  int dive_len_ = 0, dive_limit_ = 0, dive_failures_ = 0;
  uint64_t dives_ = 0, dive_wins_ = 0;
  uint64_t left_ = UINT64_MAX;  // expansions-budget units left to the running search() call
  uint64_t refine_iterations_ = 0, guide_iterations_ = 0;
  int lns_failures_ = 0;  // in a row; LNS alone gives up after many
  uint64_t units_ = 1;    // budget charged for the last expand(): an LNS step counts its work / N
  uint64_t debt_ = 0;     // expansions-budget units an LNS step overran, paid by the next search() calls
  // Of the running search() call, less the next reroot's predicted cost while refining.
  Clock::time_point deadline_ = Clock::time_point::max();
  bool timed_ = false;            // the running call has a deadline
  bool stalled_ = false;          // the last expand() found no step that fits
  enum class Step { expansion, lns, guide, prepare, insert, none };
  Step last_step_ = Step::none;   // what the last expand() did (which cost model learns)
  double last_units_ = 0;         // its size in the model's units
  StepCost expand_cost_, lns_cost_, prepare_cost_, rebase_cost_;
  StepCost insert_cost_;          // one node of an improved LNS window
  std::vector<Config> pending_;   // that window: configurations [pending_next_, end) still to insert
  size_t pending_next_ = 0;
  HNode* pending_prev_ = nullptr; // the node they continue from
  StepCost guide_tail_;           // how far past its deadline a SUO / dive step ran (ms)
  bool preparing_ = false;        // start_refining() still costing nodes
  size_t prepare_next_ = 0;       // the next node to cost
  std::vector<HNode*> path_nodes_;  // scratch: the best path's nodes (LNS)
  std::vector<Config> window_;      // scratch: an LNS window's configurations
  uint64_t solved_expansions_ = 0;
  size_t solved_explored_ = 0;
  std::vector<HNode*> queue_;                    // scratch: rewrite / rebase
  std::vector<std::pair<HNode*, int64_t>> walk_;  // scratch: rebase (node, its old g)
  Config scratch_;
  std::vector<uint8_t> immobile_;  // set_immobile()
  bool lns_wanted_ = true;         // opt_.lns as constructed (off while agents are immobile)
  std::vector<Vertex> moves_;  // scratch: children of a constraint
};

}  // namespace planner
