#pragma once
// TaskPool (LoRR 2024): pool_size tasks are revealed (lines 0..pool_size-1 of the file);
// each finished task reveals the next line (cyclic). An agent without a task is matched
// to a free task by the assigner at the start and at the end of every step in which
// something completed (goals change only then). An opened task (first errand done) stays
// with its agent until finished, as in LoRR. With `reassign`, every such step also takes
// back the tasks not yet opened and matches them again together with the free agents, so a
// task goes to whoever is nearest now, not to whoever was free when it was revealed. Goals
// still change only at steps with a completion, so RT-LaCAM's epochs stay as they are.
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
  const TaskAssigner& assigner() const { return *assigner_; }
  bool reassigns() const { return reassign_; }
  long reassignments() const { return reassignments_; }  // tasks that changed agent

  // Cost of `agent` at `pos` taking a task: distance to its first errand + its chain.
  int64_t cost(planner::Vertex pos, const Task& t);
  int revealed() const { return static_cast<int>(next_id_); }

 protected:
  void on_start(const planner::Config& positions) override;
  void on_finished(int agent, const Task& task) override;
  void after_step(const planner::Config& positions) override;

 private:
  void assign_free(const planner::Config& positions);
  int chain_length(const Task& t);

  planner::DistTable dist_;  // per errand cell, lazily (true graph distances, LRU-capped)
  int pool_size_;
  std::unique_ptr<TaskAssigner> assigner_;
  bool reassign_;
  long reassignments_ = 0;
  long next_id_ = 0;
  std::vector<int> chain_by_line_;  // -1: not yet computed
};

}  // namespace tasks
