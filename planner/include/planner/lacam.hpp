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
// The same object serves full-horizon LaCAM (search to the end, then path()),
// RT-LaCAM (search a little, move to root's child toward the top, reroot(), continue)
// and naive RT-LaCAM (reset() every iteration).
#include <functional>
#include <string>
#include <vector>

#include "planner/action_preference.hpp"
#include "planner/arena.hpp"
#include "planner/budget.hpp"
#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/explored_table.hpp"
#include "planner/hnode.hpp"
#include "planner/pibt.hpp"
#include "planner/rng.hpp"
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
};

class Lacam {
 public:
  // `dist` must outlive the search; it is shared so that naive RT-LaCAM and goal changes
  // reuse BFS tables. `pref` (optional) orders PIBT's candidate moves.
  Lacam(const Graph& g, DistTable& dist, LacamOptions opt = {}, ActionPreference* pref = nullptr);

  // Drops the tree and starts a new search rooted at `start` towards `goals`. The root's
  // PIBT priorities are `priorities` when given (a lifelong epoch carries them over, so
  // agents that waited long keep winning conflicts), else distance / N.
  void reset(const Config& start, const Config& goals, GoalTest test = {}, const float* priorities = nullptr);

  Status expand();                   // one LaCAM iteration
  Status search(const Budget& b);    // expands until solved, exhausted or out of budget (>= 1 expansion)
  Status status() const { return status_; }

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
  // RT-LaCAM's reroot: `child` (whose parent is the root) becomes the root by reversing
  // the edge. Nothing else in the tree, the explored table or the constraints changes.
  void reroot(const HNode* child);

  uint64_t expansions() const { return expansions_; }  // since construction, over all resets
  size_t explored() const { return explored_.size(); }
  size_t open_size() const { return open_.size(); }

  // Tree invariants (for tests): the root has no parent, the parent pointers of every
  // explored node lead to the root without cycles. On failure, `why` says where.
  bool check_tree(std::string* why = nullptr) const;

 private:
  HNode* new_node(const Vertex* C, HNode* parent, uint64_t hash, const float* root_priorities = nullptr);
  bool is_goal(const HNode* h) const;

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
  ExploredTable explored_;
  std::vector<HNode*> open_;
  std::vector<HNode*> all_;   // every explored node, by id
  HNode* root_ = nullptr;
  HNode* goal_ = nullptr;
  Status status_ = Status::NoSolution;
  uint64_t expansions_ = 0;
  Config scratch_;
  std::vector<Vertex> moves_;  // scratch: children of a constraint
};

}  // namespace planner
