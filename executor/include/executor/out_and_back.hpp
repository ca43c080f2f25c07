#pragma once
// OutAndBack: a lookahead between a real-time planner's commits and the ADG that cuts an
// agent's out-and-back -- u -> v (waits on v) -> u -- into waits on u, whenever no other agent
// stands on u in between. PIBT-style planners make way by stepping aside and back; in lock-step
// that costs nothing (a wait and a move are both one tick), but a physical AGV must stop to
// reverse: two hops of rest-to-rest motion, and every AGV whose hand-over waits on it waits
// that long too. On the large warehouse (200 AGVs, RT-LaCAM, 50 expansions per step) 22 % of
// the planned moves were reversals; cutting the out-and-backs inside 8 steps drops the plan's
// ADG critical path with physical move times from 352 s to ~250 s
// (scripts/closed_loop_decompose.py).
//
// Why the cut plan is still valid (vertex / swap free, moves along edges): the agent now waits
// on u where it stood before and to which it returns, and nobody else is on u meanwhile
// (checked), so no vertex conflict at u; it leaves v unvisited, which only frees v; it makes
// no move in the cut span, so it swaps with nobody; every other agent's path is unchanged. The
// span's first and last configurations keep the agent where the planner has it, so the plan
// joins the planner's at the lookahead's ends. The caller validates each configuration it
// hands on all the same (planner::Validator).
//
// Loops (`loops`, session 34): the same holds for any excursion that leaves u and comes back to
// it -- u -> v -> w -> v -> u, or around a block u -> v -> w -> x -> u -- with nobody else on u
// meanwhile: the agent waits on u, frees every cell of the excursion and makes no move in it.
// Without it, u -> v -> w -> v -> u is cut only when v is free while the agent is on w (the
// inner out-and-back first); a pass through v by someone else kept both reversals.
//
// Only configurations still in the lookahead change: those handed on (to the ADG) are fixed.
//
// Beyond one-shot cell plans (OutAndBackLimits, session 34):
//   - lifelong runs: an excursion may be an errand's visit; `keep` names the visits that must
//     stay (the agent's goal), and an excursion through one is not cut;
//   - one-at-a-time zones (rules): staying on u keeps the agent in u's zone, so an excursion
//     is cut only if nobody else is in a zone of u meanwhile (`exclusive`), besides on u.
// Headings (rotation solvers): not used there (Run::loop_adg) -- they commit one step per
// tick, so the lookahead lags their execution and empties whenever the ADG runs dry; measured
// fewer errands with it.
#include <cstddef>
#include <deque>
#include <functional>
#include <utility>

#include "planner/config.hpp"

namespace executor {

// What else a cut must respect (empty functions: nothing).
struct OutAndBackLimits {
  std::function<bool(int agent, planner::Vertex cell)> keep;         // a visit that must stay
  std::function<bool(planner::Vertex u, planner::Vertex w)> exclusive;  // u, w not held by two AGVs at once (u != w)
};

class OutAndBack {
 public:
  // tail: the last configuration handed on (the start); lookahead: configurations held back
  // (0: none, every push is handed on at once unchanged).
  // loops: cut every excursion back to u (above), not only u -> v -> u.
  OutAndBack(const planner::Config& tail, int lookahead, bool loops = true, OutAndBackLimits limits = {})
      : tail_(tail), lookahead_(lookahead), loops_(loops), limits_(std::move(limits))
  {
  }

  // A committed configuration (valid after the last one pushed). Cuts what it completes.
  void push(const planner::Config& c);
  // More than `lookahead` held: the oldest may go.
  bool full() const { return buf_.size() > static_cast<size_t>(lookahead_); }
  bool empty() const { return buf_.empty(); }
  size_t size() const { return buf_.size(); }
  // The oldest held configuration, as cut; it becomes the tail.
  planner::Config pop();
  // Drops what is held (a replan restarts the planner from `tail`).
  void reset(const planner::Config& tail)
  {
    buf_.clear();
    tail_ = tail;
  }
  long long cuts() const { return cuts_; }  // out-and-backs cut so far

 private:
  // Cuts agent i's out-and-back (with loops_: excursion) returning at buf_[e] if there is one; true if cut.
  bool cut(int i, size_t e);
  const planner::Config& at(size_t k) const { return k == 0 ? tail_ : buf_[k - 1]; }  // 0: tail

  planner::Config tail_;
  std::deque<planner::Config> buf_;
  int lookahead_;
  bool loops_;
  OutAndBackLimits limits_;
  long long cuts_ = 0;
};

}  // namespace executor
