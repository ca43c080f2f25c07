// The search's side of iterative refinement (LacamOptions::iter_refine, iter_refiner.hpp).
// In its refinement turns the search, in this order:
//  - copies the followed path into the refiner when the path changed other than by the
//    refiner's own windows (BestPath::version) -- O(T) pointers, then entered into its tables
//    in slices to each call's deadline (IterRefiner::begin / build);
//  - hands an improvement to the tree: once the copy is cheaper than what was last handed
//    out, after kIterEmitGroups groups or sooner when the change is near the root, the
//    changed steps go in as one window, inserted and spliced like a refiner thread's
//    (place_window, insert_step, BestPath::splice);
//  - else replans one group of agents, as many as fit the call's room at their learnt cost,
//    from kIterLead steps ahead of the root (the agents move on while a window is inserted).
#include <algorithm>
#include <climits>

#include "planner/lacam/lacam.hpp"

namespace planner {

namespace {
constexpr int kIterAgentUnits = 4;  // expansions charged per agent replanned (untimed budgets)
constexpr double kCopyPrior = 1e-5;  // ms per configuration x agent handed out in a window
}

bool Lacam::iter_step()
{
  if (!iter_) iter_ = std::make_unique<IterRefiner>(g_, dist_, opt_.seed + 0x5eed);
  IterRefiner& R = *iter_;
  if (iter_adopting_) return false;  // its window is still being inserted
  const auto& p = best_.nodes();
  if (!R.ready() || R.version() != best_.version()) {
    // A new copy (O(T) pointers), entered into the refiner's tables in slices to the deadline
    // (O(N) per step of the path): at N = 600 a whole copy took 2-5 ms.
    if (!R.building() || R.version() != best_.version()) {
      std::vector<const Vertex*> path(p.size());
      for (size_t t = 0; t < p.size(); ++t) path[t] = p[t]->C;
      R.begin(path, n_, root_step_, goals_, best_.version(), best_.waits());
      iter_win_ready_ = false;
      iter_since_ = 0;
      ++iter_resets_;
    }
    R.build(deadline_);
    units_ = std::max<uint64_t>(1, R.work() / static_cast<uint64_t>(std::max(n_, 1)));
    return true;
  }
  // A window, once the copy improved: soon when the change is near the agents.
  if (!iter_win_ready_ && R.cost() < R.emitted_cost()) {
    const int64_t near = R.dirty_from() - root_step_;
    if (iter_since_ >= static_cast<uint64_t>(kIterEmitGroups) || (near >= 0 && near < 2 * kIterLead)) {
      const double units = static_cast<double>(R.dirty_steps()) * n_;  // a copy out, as a copy in
      if (timed_ && !fits(iter_copy_cost_.predict_ms(units))) {
        iter_copy_cost_.forget();
        return false;
      }
      const double c0 = timed_ ? thread_cpu_ms() : 0.0;
      iter_win_ready_ = R.window(iter_win_);
      iter_since_ = 0;
      if (timed_) iter_copy_cost_.record(units, thread_cpu_ms() - c0);
      return true;
    }
  }
  if (iter_win_ready_) {
    const int r = place_window(iter_win_, iter_check_cost_, true);
    if (r == 0) return false;  // its check does not fit now
    iter_win_ready_ = false;
    if (r < 0) {  // the copy no longer matches what the agents follow
      ++iter_refused_;
      R.clear();
      return r == -2;
    }
    iter_adopting_ = true;
    if (!timed_) insert_step();  // no deadline: at once (deterministic runs)
    return true;
  }
  // One group: as many agents as fit at the learnt cost of one (an expansion's, until known).
  iter_cost_.set_prior(expand_cost_.rate());
  int k = INT_MAX;
  if (timed_) {
    const double fit = iter_cost_.units_within(room_ms());
    if (fit < 1) {
      iter_cost_.forget();
      return false;
    }
    k = static_cast<int>(std::min<double>(fit, INT_MAX));
  }
  const double c0 = timed_ ? thread_cpu_ms() : 0.0;
  R.step(root_step_ + kIterLead, deadline_, k);
  if (R.last_group() == 0) return false;  // nothing left to replan ahead of the agents
  if (timed_) iter_cost_.record(R.last_group(), thread_cpu_ms() - c0);
  ++iter_since_;
  // In expansions: an agent's SIPP took about four expansions' time (warehouse-10-20-10-2-1
  // N = 500, 1 ms: 0.2 ms against 0.05); its work count (states, interval scans) is no
  // measure of time, the scans being cheap per step.
  units_ = static_cast<uint64_t>(kIterAgentUnits * R.last_group());
  return true;
}

void Lacam::iter_spliced(bool ok)
{
  iter_adopting_ = false;
  if (ok) {
    ++iter_windows_;
    iter_->set_version(best_.version());  // the copy is the path now, with its later changes
  } else {
    ++iter_refused_;
    iter_->clear();
  }
}

}  // namespace planner
