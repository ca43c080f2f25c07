#pragma once
// ExecutedPlan: the configurations the AGVs were committed to, C^0 .. C^T -- plan.txt's
// solution, the physical bound's input, and what the stuck-AGV replan rewrites.
//
// A one-shot run keeps all of them. A lifelong run would grow by one configuration per
// commit without end (4 KB per tick at 1000 AGVs), so it keeps only the configurations a
// replan may still rewrite -- from the oldest plan step some AGV has not finished
// (settle()) -- plus `keep` more, and hands the older, final ones to `on_final` (the bound)
// and to a spill file that becomes plan.txt's body at the end. Memory stays bounded
// however long the run; plan.txt is the same as if all had been kept (tested).
#include <cstddef>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace controller {

class ExecutedPlan {
 public:
  ExecutedPlan() = default;
  ExecutedPlan(const ExecutedPlan&) = delete;
  ExecutedPlan& operator=(const ExecutedPlan&) = delete;
  ~ExecutedPlan();  // removes a spill file copy_spilled() did not take (a run cut short)

  // A fresh plan C^0 = start, everything kept.
  void start(const planner::Config& c0);
  // Bounded: at least `keep` configurations stay in memory; older final ones go to
  // `on_final` and, unless spill_path is empty, to that file in plan.txt's line format.
  void bound(size_t keep, std::function<void(const planner::Config&)> on_final, const planner::Graph* g,
             const std::string& spill_path);

  void push_back(const planner::Config& c) { kept_.push_back(c); }
  size_t size() const { return first_ + kept_.size(); }  // T + 1
  size_t first() const { return first_; }                // C^first is the oldest kept
  planner::Config& at(size_t t) { return kept_[t - first_]; }
  const planner::Config& at(size_t t) const { return kept_[t - first_]; }
  const planner::Config& back() const { return kept_.back(); }
  void resize(size_t n) { kept_.resize(n - first_); }
  const std::vector<planner::Config>& kept() const { return kept_; }

  // Configurations before C^t are final (no replan rewrites them): in a bounded plan they
  // leave memory once `keep` more than that have piled up.
  void settle(size_t t);
  // The spill file's lines (plan.txt's body from C^0 to C^first-1) into `out`, then the
  // file is removed. Throws planner::OutputError if it could not be written or read.
  void copy_spilled(std::ostream& out);

 private:
  std::vector<planner::Config> kept_;
  size_t first_ = 0, keep_ = 0;
  bool bounded_ = false;
  std::function<void(const planner::Config&)> on_final_;
  const planner::Graph* g_ = nullptr;
  std::string spill_path_;
  std::ofstream spill_;
};

}  // namespace controller
