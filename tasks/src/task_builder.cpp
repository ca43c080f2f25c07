#include "tasks/task_builder.hpp"

#include <random>
#include <stdexcept>

namespace tasks {

TaskFile random_task_file(const std::vector<std::vector<planner::Vertex>>& pools, int count, int errands,
                          uint64_t seed, const std::string& name)
{
  if (count < 1) throw std::invalid_argument("random tasks: count must be >= 1");
  if (errands < 1) throw std::invalid_argument("random tasks: errands must be >= 1");
  if (pools.empty()) throw std::invalid_argument("random tasks: no errand cells");
  for (const auto& p : pools)
    if (p.empty()) throw std::invalid_argument("random tasks: an empty errand pool");
  TaskFile f;
  f.path = name;
  std::mt19937_64 rng(seed);
  for (int t = 0; t < count; ++t) {
    std::vector<planner::Vertex> e;
    for (int i = 0; i < errands; ++i) {
      const auto& p = pools[static_cast<size_t>(i) % pools.size()];
      e.push_back(p[rng() % p.size()]);
    }
    f.tasks.push_back(std::move(e));
    f.lines.push_back(t);
  }
  return f;
}

TaskFile listed_task_file(std::vector<std::vector<planner::Vertex>> tasks, const std::string& name)
{
  if (tasks.empty()) throw std::invalid_argument("listed tasks: no task");
  TaskFile f;
  f.path = name;
  for (size_t i = 0; i < tasks.size(); ++i) {
    if (tasks[i].empty()) throw std::invalid_argument("listed tasks: task " + std::to_string(i) + " has no errand");
    f.lines.push_back(static_cast<int>(i));
  }
  f.tasks = std::move(tasks);
  return f;
}

}  // namespace tasks
