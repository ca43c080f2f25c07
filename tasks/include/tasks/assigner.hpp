#pragma once
// TaskAssigner: who takes which task in `pool` mode. The pool asks it to match free agents
// (rows) to unassigned tasks (columns) under cost(i, j) = true graph distance from agent i
// to task j's first errand + the length of j's errand chain. Each task goes to at most one
// agent; an agent gets -1 only when there are fewer tasks than agents. A cost of
// kForbidden or more (an errand the agent cannot reach, a task it may not steal) is no
// match: the caller skips it, and the greedy assigner leaves the task to the next agent.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tasks {

constexpr int64_t kForbidden = int64_t{1} << 40;

using CostFn = std::function<int64_t(int agent_row, int task_col)>;

class TaskAssigner {
 public:
  virtual ~TaskAssigner() = default;
  virtual std::string name() const = 0;
  // Column per row (-1: none).
  virtual std::vector<int> assign(int rows, int cols, const CostFn& cost) = 0;
};

// "greedy" or "hungarian" (k_nearest: candidate tasks per agent for the matching, see
// HungarianAssigner). Throws std::invalid_argument on other names.
std::unique_ptr<TaskAssigner> make_assigner(const std::string& name, int k_nearest = 32);

}  // namespace tasks
