#include "executor/rotation_execution.hpp"

#include <algorithm>
#include <stdexcept>

#include "planner/heading.hpp"
#include "planner/validator.hpp"

namespace executor {

using planner::heading_of_move;
using planner::turn_toward;

RotationExecution::RotationExecution(const planner::Graph& g, const planner::Config& starts, int window)
    : g_(g), window_(window), pos_(starts), heading_(starts.size(), 0), progress_(starts.size(), 0),
      visits_(static_cast<size_t>(g.size()))
{
  if (window < 1) throw std::invalid_argument("rotation window must be >= 1");
  if (!g.is_grid()) throw std::invalid_argument("the rotation model needs a grid graph");
  plan_.push_back(starts);
  for (int i = 0; i < static_cast<int>(starts.size()); ++i) visits_[starts[i]].push_back({i, 0});
}

void RotationExecution::push(const planner::Config& next)
{
  const planner::Config& last = plan_.back();
  ++frontier_;
  for (int i = 0; i < static_cast<int>(next.size()); ++i)
    if (next[i] != last[i]) visits_[next[i]].push_back({i, frontier_});
  plan_.push_back(next);
}

bool RotationExecution::moves(int i)
{
  enum { Unknown = 0, Visiting, Yes, No };
  if (!want_[i]) return false;
  if (memo_[i] == Visiting) return true;  // a cycle of followers: all go together
  if (memo_[i] != Unknown) return memo_[i] == Yes;
  memo_[i] = Visiting;
  const std::vector<Visit>& q = visits_[target_[i]];
  const long enter = progress_[i] + 1;
  auto mine = [&](const Visit& v) { return v.agent == i && v.start == enter; };
  bool ok = false;
  if (mine(q.front())) ok = true;
  else if (q.size() >= 2 && mine(q[1])) {
    const int j = q.front().agent;  // earlier visitor: must be there and leave now
    ok = pos_[j] == target_[i] && moves(j);
  }
  memo_[i] = ok ? Yes : No;
  return ok;
}

void RotationExecution::step()
{
  const int n = static_cast<int>(pos_.size());
  actions_.assign(static_cast<size_t>(n), 'W');
  want_.assign(static_cast<size_t>(n), 0);
  memo_.assign(static_cast<size_t>(n), 0);
  target_.assign(static_cast<size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    while (progress_[i] < frontier_ && at(progress_[i] + 1, i) == pos_[i]) ++progress_[i];  // plan waits are free
    if (progress_[i] == frontier_) continue;
    target_[i] = at(progress_[i] + 1, i);
    const int d = heading_of_move(g_, pos_[i], target_[i]);
    if (d != heading_[i]) actions_[i] = turn_toward(heading_[i], d);
    else want_[i] = 1;
  }
  std::vector<int> movers;
  for (int i = 0; i < n; ++i)
    if (moves(i)) movers.push_back(i);
  for (int i : movers) {
    std::vector<Visit>& q = visits_[pos_[i]];
    q.erase(q.begin());  // i's visit of its old cell ends (it was the front one)
    pos_[i] = target_[i];
    ++progress_[i];
    actions_[i] = 'F';
  }
  for (int i = 0; i < n; ++i) {
    heading_[i] = planner::heading_after(heading_[i], actions_[i]);
  }
  min_progress_ = n > 0 ? *std::min_element(progress_.begin(), progress_.end()) : frontier_;
  while (base_ < min_progress_) {
    plan_.erase(plan_.begin());
    ++base_;
  }
}

RotationRun run_with_rotation(const planner::Graph& g, const std::vector<planner::Config>& plan)
{
  RotationRun out;
  if (plan.empty()) return out;
  RotationExecution ex(g, plan.front(), static_cast<int>(std::max<size_t>(plan.size(), 1)));
  for (size_t k = 1; k < plan.size(); ++k) ex.push(plan[k]);
  std::vector<long> last(plan.front().size(), 0);
  // Every robot needs at most 3 steps per plan step (two turns and a move) once the ones
  // before it are through: bounds the loop even if something were wrong.
  const long limit = 3 * static_cast<long>(plan.size()) * static_cast<long>(plan.front().size()) + 3;
  for (long t = 1; ex.positions() != plan.back() && t <= limit; ++t) {
    const planner::Config before = ex.positions();
    ex.step();
    const std::string& act = ex.actions();
    const std::string err = planner::Validator::check_transition(g, before, ex.positions());
    if (!err.empty() && out.error.empty()) out.error = "step " + std::to_string(t) + ": " + err;
    for (size_t i = 0; i < act.size(); ++i) {
      if (act[i] != 'W') last[i] = t;
      out.turns += act[i] == 'R' || act[i] == 'C';
    }
    out.makespan = t;
  }
  if (ex.positions() != plan.back() && out.error.empty()) out.error = "the robots did not reach the plan's end";
  for (long l : last) out.soc += l;
  return out;
}

}  // namespace executor
