#include "tasks/task_pool.hpp"

namespace tasks {

TaskPool::TaskPool(std::shared_ptr<const TaskFile> file, const planner::Graph& g, int pool_size,
                   std::unique_ptr<TaskAssigner> assigner, bool reassign)
    : TaskManager(std::move(file)), dist_(g), pool_size_(pool_size), assigner_(std::move(assigner)), reassign_(reassign)
{
  chain_by_line_.assign(file_->size(), -1);
  // Keep the tables of the tasks being matched plus a cache; drop the rest (chain lengths
  // are computed once per file line and would otherwise keep a table per errand cell).
  dist_.set_max_tables(static_cast<size_t>(pool_size_) + 256);
}

int TaskPool::chain_length(const Task& t)
{
  int& c = chain_by_line_[t.line];
  if (c < 0) {
    c = 0;
    for (size_t k = 1; k < t.errands.size(); ++k) c += dist_.from_goal(t.errands[k], t.errands[k - 1]);
  }
  return c;
}

int64_t TaskPool::cost(planner::Vertex pos, const Task& t)
{
  return static_cast<int64_t>(dist_.from_goal(t.errands[t.next], pos)) + chain_length(t);
}

void TaskPool::on_start(const planner::Config& positions)
{
  for (int k = 0; k < pool_size_; ++k) add_task(make_task(next_id_++));
  assign_free(positions);
}

void TaskPool::on_finished(int, const Task&)
{
  add_task(make_task(next_id_++));
}

void TaskPool::after_step(const planner::Config& positions)
{
  if (!reassign_) return assign_free(positions);
  std::vector<int> before(num_agents(), -1);  // task id each agent held unopened
  for (int a = 0; a < num_agents(); ++a) {
    const int s = holding_[a];
    if (s < 0 || slot(s).next > 0) continue;
    before[a] = static_cast<int>(slot(s).id);
    release(a);
  }
  assign_free(positions);
  for (int a = 0; a < num_agents(); ++a)
    if (before[a] >= 0 && (holding_[a] < 0 || slot(holding_[a]).id != before[a])) ++reassignments_;
}

void TaskPool::assign_free(const planner::Config& positions)
{
  std::vector<int> agents, cols;
  for (int a = 0; a < num_agents(); ++a)
    if (holding_[a] < 0) agents.push_back(a);
  if (agents.empty()) return;
  for (int s : live_slots())
    if (slot(s).agent < 0) cols.push_back(s);
  if (cols.empty()) return;
  planner::Config in_use;
  for (int s : cols) in_use.push_back(slot(s).errands[slot(s).next]);
  dist_.set_goals(in_use);  // marks their tables in use; evicts idle ones over the cap
  const std::vector<int> match = assigner_->assign(static_cast<int>(agents.size()), static_cast<int>(cols.size()),
                                                   [&](int i, int j) { return cost(positions[agents[i]], slot(cols[j])); });
  for (size_t i = 0; i < agents.size(); ++i)
    if (match[i] >= 0) give(agents[i], cols[match[i]]);
}

}  // namespace tasks
