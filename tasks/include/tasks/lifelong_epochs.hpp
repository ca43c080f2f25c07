#pragma once
// LifelongEpochs: the task and epoch part of a lifelong run, one for every back end. The
// grid's LifelongRun (lifelong_run.hpp: rtlacam-lifelong, Python) and the SUMO controller's
// lifelong mode (controller/src/run.hpp) both run their epochs through it; each keeps its
// own execution (the step budget is one object too: step_budget.hpp). The seam is the LoRR start kit's (a task scheduler of a few
// methods beside the planner and the executor):
//
//   start     the task layer on the robots' start cells, before the planner is built:
//             errand times and stalls watched (errand_stalls.hpp), the free-flow bound
//             (free_flow.hpp, priced by the back end), the first assignment
//   complete  errands done on the robots' real (executed) cells at the end of step t
//             (TaskManager::update), timed as the task layer's work (task_ms); says whether
//             goals changed (completions, or station queues redone without one)
//   start_epoch  the priority hints (urgency.hpp), then set_goals with the lifelong goal test
//             (lifelong_goal.hpp): a fresh tree at the planner's current configuration
//   prefetch  the goals to come, nearest agent first: the cell tables' and the rotation
//             solvers' (cell, heading) tables
//   record    epochs, the step's completions, the longest run of steps without one
//   count     per step on the real cells: how long agents keep one goal, the crowd heading
//             for one errand cell, agents waiting on their queue cells, idle and parked
//             ones (EpochCounts: the controller's metrics.json and rtlacam-lifelong's log)
//
// Why the rest stays with each back end: a grid step and a SUMO tick are timed apart
// (one StepBudget per grid step, one per SUMO step in Run::step); the grid executes
// on Execution (delays, rotation windows), SUMO on the Commander, Driver, ADG and Safety over
// physical AGVs, with traffic rules that change the epoch's goals (closed goals wait) and a
// search slice, the validator's goals and goal markers after set_goals. Both prefetch: the
// grid in its StepBudget's spare time, the controller in its SUMO steps' (planner.prefetch,
// off by default there: controller/README.md "Prefetch").
#include <memory>
#include <vector>

#include "planner/dist_cache.hpp"
#include "planner/graph.hpp"
#include "planner/realtime_planner.hpp"
#include "tasks/free_flow.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/task_manager.hpp"

namespace planner {
class RotationPlanner;
}

namespace tasks {

// The epoch start itself: p's priority hints, then `goals` (the task layer's, or what a back
// end makes of them) with the lifelong goal test at p's current configuration.
void start_epoch(const TaskManager& tasks, planner::RealtimePlanner& p, const planner::Config& goals);

class LifelongEpochs {
 public:
  // Counts into r (epochs, events, task_ms, setup_ms stays the caller's).
  LifelongEpochs(TaskManager& tasks, LifelongResult& r) : tasks_(tasks), r_(r) {}

  // Stalls watched on g (unless already), `cache` shared with the task layer when given
  // (the pool's assigner, the queues), the free-flow bound, the first tasks; one epoch.
  void start(const planner::Graph& g, const planner::Config& starts, std::unique_ptr<FreeFlowBound> bound,
             std::shared_ptr<planner::DistCache> cache = nullptr);
  // End of step t, the robots on `real`: true when the goals changed (a new epoch is due).
  bool complete(long t, const planner::Config& real);
  const std::vector<Event>& completed() const { return ev_; }  // the last complete()'s
  void start_epoch(planner::RealtimePlanner& p) const { tasks::start_epoch(tasks_, p, tasks_.goals()); }
  void start_epoch(planner::RealtimePlanner& p, const planner::Config& goals) const { tasks::start_epoch(tasks_, p, goals); }
  // The goals to come, nearest agent first: for cell tables each next goal's table must
  // reach the current goal (where the agent will be), measured from `at` (the plan frontier).
  void prefetch(planner::DistCache& cache, const planner::Config& at) const;
  void prefetch(planner::RotationPlanner& rot) const;
  // The last complete()'s events into the result; `epoch`: a new epoch started.
  void record(bool epoch);
  // The same in two parts, for a back end that counts an errand later than the task layer
  // completes it (the controller's plan completions: when the AGV has executed it).
  void record_epoch(bool epoch) { r_.epochs += epoch ? 1 : 0; }
  void record_events(const std::vector<Event>& events) { r_.events.insert(r_.events.end(), events.begin(), events.end()); }
  long long max_gap() const { return max_gap_; }  // longest run of steps without a completion
  // After step t's epoch phases, the agents on `real`.
  void count(long t, const planner::Config& real);
  const EpochCounts& counts() const { return counts_; }

 private:
  TaskManager& tasks_;
  LifelongResult& r_;
  std::vector<Event> ev_;
  long long last_completion_ = 0, max_gap_ = 0;
  EpochCounts counts_;
  std::vector<long long> goal_start_;  // count(): the step each agent's current goal began
  planner::Config goal_;
  std::vector<uint8_t> is_station_;  // the task file's errand cells
  std::vector<int> heading_count_;   // agents heading to each cell this step (zeroed after use)
};

}  // namespace tasks
