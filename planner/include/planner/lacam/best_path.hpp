#pragma once
// BestPath: under Objective::soc (objective.hpp), the path of LaCAM* nodes the agents follow,
// from the root to a goal node, priced by the standard SOC still to pay along it.
//
// Why apart from the tree: the standard SOC is no edge cost (an agent's wait on its goal is
// charged only if it leaves later), so LaCAM*'s g, rewiring and reroots keep the loss and
// stay exact, while the path that is followed changes only when a candidate is cheaper in
// the standard SOC: the goal's tree path (priced by a backward scan, resumable node by node,
// O(N) per node) or an improved LNS window spliced in (priced for the replanned agents only).
//
// Cost to pay from the root: an agent off its goal somewhere on the path pays up to its last
// arrival (last_off + 1) plus, if it stands on its goal at the root, the steps it has waited
// there since it arrived (they were free only as long as it stayed); an agent that stays on
// its goal pays nothing. So a path that parks an agent and pushes it off later is charged
// for the whole wait, as Validator::sum_of_costs charges the executed plan.
#include <cstdint>
#include <vector>

#include "planner/config.hpp"
#include "planner/lacam/hnode.hpp"

namespace planner {

class BestPath {
 public:
  // No path; every agent at the root has waited 0 steps on its goal.
  void reset(const Config& goals);
  bool empty() const { return nodes_.empty(); }
  const std::vector<HNode*>& nodes() const { return nodes_; }
  int64_t cost() const { return cost_; }
  // The last index of nodes() where agent i is off its goal (-1: never): it stays on its
  // goal from every later index on.
  int32_t last_off(int i) const { return last_[i]; }
  // Steps agent i has stood on its goal at the root since it arrived (charged if it leaves).
  const int32_t* waits() const { return wait_.data(); }
  // Counts the changes of the path other than advance()'s trimming of its first node (a new
  // path adopted, a window spliced, the path dropped): a refiner thread's copy (refine_thread.hpp)
  // is still the same path while this has not changed.
  uint64_t version() const { return version_; }

  // The root moved from `from` to `to` (a neighbour): the waits follow; the path and the
  // candidate keep their tails if `to` is their second node, else they are dropped -- but
  // with `carry` a candidate that starts at `from` goes on from `to` back to `from` (the
  // tree path after a reroot, the move being reversible). Its scan runs from the end, so
  // nothing scanned is lost, and a candidate that is always cut by the next move still
  // gets priced. Returns true when it carried one.
  bool advance(const HNode* from, HNode* to, bool carry = false);

  // Starts pricing `p` (the root first, a goal node last); price_node() scans it.
  void start_candidate(std::vector<HNode*> p);
  bool pricing() const { return pricing_; }
  // Scans the candidate's next node from its end (O(N)); when all are scanned, adopts it if
  // there is no path or it is cheaper, and returns true.
  bool price_node();

  // The path with its nodes after `from` replaced by `window` (window.back() is the path's
  // own node there), where only `agents` moved differently: adopted, and true, unless
  // costlier (an LNS window of the same standard SOC has a lower loss).
  bool splice(const HNode* from, const std::vector<HNode*>& window, const std::vector<int>& agents);

 private:
  int64_t price(const std::vector<int32_t>& last) const;

  Config goals_;
  int n_ = 0;
  std::vector<HNode*> nodes_;
  std::vector<int32_t> last_;   // per agent, index of nodes_
  int64_t cost_ = 0;
  std::vector<int32_t> wait_;   // per agent: steps on its goal at the root since it arrived
  std::vector<HNode*> cand_;
  std::vector<int32_t> cand_end_;  // per agent: distance from the candidate's end of its last step off the goal, -1 unseen
  size_t scanned_ = 0;             // candidate nodes scanned, from the end
  bool pricing_ = false;
  uint64_t version_ = 0;
};

}  // namespace planner
