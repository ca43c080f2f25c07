#pragma once
// TaskPool (LoRR 2024): pool_size tasks are revealed (lines 0..pool_size-1 of the file);
// each finished task reveals the next line (cyclic). An agent without a task is matched
// to a free task by the assigner at the start and at the end of every step in which
// something completed (goals change only then). An opened task (first errand done) stays
// with its agent until finished, as in LoRR. With `reassign`, a free agent may also take a
// task that is not yet opened from its holder when it is strictly nearer to the task's first
// errand; the holder is then free and matched in the next round (at most 8 rounds a step).
// The work stays O(free agents x unopened tasks), as without reassignment, so it scales to
// LoRR's 10,000 agents (a full rematch of every unopened task each step does not). Goals
// still change only at steps with a completion, so RT-LaCAM's epochs stay as they are.
// With station queues (TaskManager::set_queues) a task is handed out only while each of
// its stations holds fewer tasks than the admission limit (admissible()): the rest of the
// fleet stays idle (parked) instead of queueing at saturated stations.
// A task handed back (task_manager.hpp: a critical charge, a closure) is matched again from
// its next errand, opened or not; no agent is matched to an errand it cannot reach. While
// closures cut errands off, tasks no agent can reach do not count against pool_size: the
// pool reveals more (up to 2 x pool_size live), else a long closure of one station fills the
// pool with its tasks and idles the fleet; it shrinks back as tasks finish after the closure.
#include <memory>

#include "planner/dist_table.hpp"
#include "tasks/assigner.hpp"
#include "tasks/task_manager.hpp"

namespace tasks {

class TaskPool : public TaskManager {
 public:
  TaskPool(std::shared_ptr<const TaskFile> file, const planner::Graph& g, int pool_size,
           std::unique_ptr<TaskAssigner> assigner, bool reassign = false);
  std::string mode() const override { return "pool"; }
  bool reassigns_for_closures() const override { return true; }
  const TaskAssigner& assigner() const { return *assigner_; }
  bool reassigns() const { return reassign_; }
  long reassignments() const { return reassignments_; }  // tasks that changed agent
  long handovers() const { return handovers_; }  // stall handovers (UrgencyOptions::swap_after)

  // Cost of `agent` at `pos` taking a task: distance to its first errand + its chain.
  int64_t cost(planner::Vertex pos, const Task& t);
  int revealed() const { return static_cast<int>(next_id_); }
  void share_dist_cache(std::shared_ptr<planner::DistCache> cache) override
  {
    share_queue_cache(cache);
    dist_.share(std::move(cache));
  }

 protected:
  void on_start(const planner::Config& positions) override;
  void on_finished(int agent, const Task& task) override;
  void after_step(const planner::Config& positions) override;
  void exchange_tasks(const planner::Config& positions) override { hand_over_stalled(positions); }

 private:
  void assign_free(const planner::Config& positions);
  void top_up(const planner::Config& positions);  // closures: reveal past the tasks nobody can reach
  void steal_rounds(const planner::Config& positions);  // assign_free with reassignment
  // Admission (station queues on, QueueOptions::admission): of the unassigned tasks among
  // `cols` (ascending task id), keeps the oldest whose every remaining errand station
  // holds fewer than the limit of held tasks with an errand left there; assigned ones stay.
  std::vector<int> admissible(const std::vector<int>& cols) const;
  int chain_length(const Task& t);
  // Stall handover (UrgencyOptions::swap_after = T > 0). In a crowd at a station, which
  // agent gets in next is decided by the planner's priorities, which reset at every epoch:
  // the nearest agent wins, and one at the back can lose for the whole run while newcomers
  // pass it (large_warehouse_lifelong: a pick-up errand stalled 469 of 500 ticks three
  // cells from its station's stub). The errand, not the agent, is what waits. So an
  // errand not yet opened, stalled >= T ticks (ErrandStalls), passes to the nearest agent
  // strictly nearer its cell that heads for the same cell with a task not yet opened and
  // stalled less, and nearer than the errand has ever been (ErrandStalls::best: passing it
  // on never undoes its progress); that agent's task passes back. Both goals stay, so the
  // planner, its epoch and the traffic are untouched: within a station's crowd the oldest
  // errand rides with the agent nearest to being served (first come, first served per
  // station). The most stalled errand picks first; an agent swaps at most once a step.
  // Opened errands (a load on board) never move.
  void hand_over_stalled(const planner::Config& positions);
  // UrgencyOptions::load_cost x (tasks held with an errand left at each remaining errand
  // cell of task cols[j]), per j: the matching spreads the fleet over the stations.
  std::vector<int64_t> load_costs(const std::vector<int>& cols);
  std::vector<int> load_;  // per vertex, scratch (all 0 between calls)

  planner::DistTable dist_;  // per errand cell, lazily (true graph distances, LRU-capped)
  int pool_size_;
  std::unique_ptr<TaskAssigner> assigner_;
  bool reassign_;
  long reassignments_ = 0;
  long handovers_ = 0;
  long next_id_ = 0;
  std::vector<int> chain_by_line_;  // -1: not yet computed
};

}  // namespace tasks
