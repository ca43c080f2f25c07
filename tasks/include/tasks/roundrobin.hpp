#pragma once
// RoundRobin (LoRR 2023): agent i holds tasks i, i+N, i+2N, ... of the task file (cyclic),
// one at a time; no scheduler. With one-errand tasks (the 2023 files) a task is an errand.
// An agent that needs charge after a task (battery.hpp), or whose charge does not cover its
// next task and the way on to a charger (the task check, BatteryOptions::task_check), gets
// its next one when it leaves the charger; one that hands its task back at a critical
// charge resumes that task there. A
// closure does not reassign here (the stream is the agent's own): the agent waits.
#include <vector>

#include "tasks/task_manager.hpp"

namespace tasks {

class RoundRobin : public TaskManager {
 public:
  using TaskManager::TaskManager;
  std::string mode() const override { return "roundrobin"; }
  // Also each agent's next task (i + N) when it is on its current task's last errand.
  std::vector<Upcoming> upcoming() const override;

 protected:
  void on_start(const planner::Config& positions) override;
  void on_finished(int agent, const Task& task) override;
  void on_charged(int agent) override;
  void on_dropped(int agent, int s) override;

 private:
  // Gives `agent` (at `at`) task `id`, or defers it while the agent charges first: it needs
  // charge, or cannot afford the task (BatteryOptions::task_check).
  void next_task(int agent, long id, planner::Vertex at);
  std::vector<long> deferred_;  // per agent: its next task's id while it charges, -1
  std::vector<int> dropped_;    // per agent: the slot of the task it handed back, -1
};

}  // namespace tasks
