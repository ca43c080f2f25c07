#pragma once
// ErrandStalls: how long errands wait (issue 24: "errands never stalling more than K ticks").
// Only errands of tasks count: an idle, parked or charging agent holds none, so standing
// still there is no stall.
//
// Per errand (a task's errand, one open at a time per task):
//  - open ticks: from the end of the step its task was first given to an agent (first
//    errand) or its previous errand completed (later ones) to the end of the step it
//    completes; an errand still open at the end counts to the end.
//  - stall ticks: the longest stretch of steps in which the errand's holder got no closer
//    to the errand's cell than it had been. Precisely, with d_t the distance (the graph's
//    shortest path, move costs included, along arcs) from the holder's cell to the errand
//    cell at the end of step t: the errand starts with a progress mark at its opening step
//    and best = d there; step t is progress when d_t < best (best = d_t, a new mark);
//    completion is the last mark. The stall is the longest gap between consecutive marks
//    (the last gap ends at the run's end for an open errand). A new holder (the errand was
//    handed back and matched again) sets best to its own distance without a mark: the
//    errand keeps stalling until someone gets closer. Waiting in a station's queue or for a
//    closure counts: the errand does not get done.
// K of a run = the max stall; the open ticks say how long errands take end to end.
//
// Distances come from a DistTable: a cache of its own on `g`, or the planner's (share()):
// then the tables the planner grows anyway; queries here are exact (they grow the table past
// any deadline), so the metric never depends on timing.
#include <memory>
#include <unordered_map>
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_table.hpp"

namespace tasks {

class ErrandStalls {
 public:
  explicit ErrandStalls(const planner::Graph& g) : g_(g), dist_(g) {}
  void share(std::shared_ptr<planner::DistCache> cache) { dist_.share(std::move(cache)), shared_ = true; }

  // What agent a holds at the end of a step: task id (-1: none), errand index, errand cell.
  struct Held {
    long task = -1;
    int errand = 0;
    planner::Vertex cell = -1;
  };
  // End of step t: errand `errand` of task `task` completed (before observe() of step t).
  void completed(long t, long task, int errand);
  // End of step t (0: the start): each agent's holding, where it stands.
  void observe(long t, const std::vector<Held>& held, const planner::Config& positions);

  // Stall ticks so far of the open errand of `task` (0 when none is open). Sticky: the
  // longest stall the errand has had so far (UrgencyOptions::sticky), not only the current one.
  long long stalled(long t, long task) const;
  void set_sticky(bool on) { sticky_ = on; }
  // The longest stall of the open errand of `task` so far, whatever `sticky` (escalation.hpp).
  long long longest(long t, long task) const;
  // The step of its last progress mark (its opening step before any); -1 when none is open.
  long last_mark(long task) const;
  // The nearest the holder of `task`'s open errand has been to its cell (a new holder starts
  // from its own distance); -1 when none is open.
  int32_t best(long task) const;
  // The distance this metric measures from v to `cell` (its graph, exact whatever the
  // deadline), and that graph: the driven one, which may lack the planner's routing costs
  // (tasks.urgency.mouth_cost, stub_mouths.hpp), so that a routing cost never changes K.
  int32_t distance(planner::Vertex cell, planner::Vertex v) const;
  const planner::Graph& graph() const { return g_; }

  struct Summary {
    long long errands = 0;                    // completed + still open
    long long max_open = 0, p99_open = 0;     // open ticks
    long long max_stall = 0, p99_stall = 0;   // stall ticks (K = max_stall)
  };
  // Completed errands and those open at step t (counted to t).
  Summary summary(long t) const;

 private:
  struct Open {
    int errand = 0;
    long opened = 0, mark = 0;  // opening step, last progress mark
    int32_t best = 0;
    int holder = -1;
    long long max_gap = 0;      // longest gap between marks so far
  };
  const planner::Graph& g_;
  planner::DistTable dist_;
  std::unordered_map<long, Open> open_;  // task id -> its open errand
  bool sticky_ = false;
  std::vector<long long> open_ticks_, stall_ticks_;  // completed errands
  planner::Config goals_;
  bool shared_ = false;  // the planner's cache: its owner caps it
};

}  // namespace tasks
