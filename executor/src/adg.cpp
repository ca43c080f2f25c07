#include "executor/adg.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace executor {

Adg::Adg(const planner::Config& start)
    : tail_(start), at_(start), queue_(start.size()), head_(start.size(), 0)
{
}

int Adg::append(const planner::Config& next)
{
  if (next.size() != tail_.size()) throw std::invalid_argument("Adg::append: configuration of the wrong size");
  const int n = num_agents();
  planner::Vertex max_v = 0;
  for (int i = 0; i < n; ++i) max_v = std::max({max_v, tail_[i], next[i]});
  if (static_cast<size_t>(max_v) >= last_leave_.size()) last_leave_.resize(static_cast<size_t>(max_v) + 1, -1);

  // All leaves of this step first: an agent entering a cell another leaves in the same
  // step (following) depends on that leave.
  const int first = num_actions();
  for (int i = 0; i < n; ++i) {
    if (tail_[i] == next[i]) continue;
    Action a;
    a.agent = i;
    a.from = tail_[i];
    a.to = next[i];
    a.step = steps_;
    a.prev = queue_[i].empty() ? -1 : queue_[i].back();
    queue_[i].push_back(num_actions());
    actions_.push_back(a);
  }
  const int last = num_actions();
  for (int id = first; id < last; ++id) last_leave_[actions_[id].from] = id;
  for (int id = first; id < last; ++id) {
    Action& a = actions_[id];
    const int h = last_leave_[a.to];
    if (h >= 0 && actions_[h].agent != a.agent) a.handover = h;
  }

  // Rotation cycles within this step: following same-step hand-overs from an action
  // returns to it. Each action has at most one hand-over, so walking finds each cycle.
  for (int id = first; id < last; ++id) {
    if (actions_[id].group >= 0) continue;
    std::vector<int> path;
    int x = id;
    while (x >= first && actions_[x].group < 0 && std::find(path.begin(), path.end(), x) == path.end()) {
      path.push_back(x);
      x = actions_[x].handover;
    }
    if (x < first || actions_[x].group >= 0) continue;
    auto it = std::find(path.begin(), path.end(), x);
    const int g = static_cast<int>(groups_.size());
    groups_.emplace_back(it, path.end());
    for (int m : groups_.back()) actions_[m].group = g;
  }
  tail_ = next;
  ++steps_;
  return last - first;
}

int Adg::next_action(int agent) const
{
  const auto& q = queue_[agent];
  return head_[agent] < q.size() ? q[head_[agent]] : -1;
}

bool Adg::prev_done(int id) const
{
  const int p = actions_[id].prev;
  if (p < 0) return true;
  if (actions_[p].group < 0) return dep_done(p);
  for (int m : groups_[actions_[p].group])
    if (actions_[m].state != State::Done) return false;
  return true;
}

bool Adg::outside_deps_done(int id) const
{
  const Action& a = actions_[id];
  if (!prev_done(id)) return false;
  if (a.handover >= 0 && !(a.group >= 0 && actions_[a.handover].group == a.group) && !dep_done(a.handover)) return false;
  return true;
}

bool Adg::released(int id) const
{
  const Action& a = actions_[id];
  if (a.state != State::Pending) return false;
  if (a.group < 0) return outside_deps_done(id);
  for (int m : groups_[a.group])
    if (actions_[m].state != State::Pending || !outside_deps_done(m)) return false;
  return true;
}

bool Adg::outside_deps_started(int id) const
{
  const Action& a = actions_[id];
  if (!prev_done(id)) return false;
  if (a.handover >= 0 && !(a.group >= 0 && actions_[a.handover].group == a.group) &&
      actions_[a.handover].state == State::Pending)
    return false;
  return true;
}

bool Adg::released_following(int id) const
{
  const Action& a = actions_[id];
  if (a.state != State::Pending) return false;
  if (a.group < 0) return outside_deps_started(id);
  for (int m : groups_[a.group])
    if (actions_[m].state != State::Pending || !outside_deps_started(m)) return false;
  return true;
}

bool Adg::may_finish(int id) const
{
  const Action& a = actions_[id];
  return a.state == State::Running &&
         (a.handover < 0 || (a.group >= 0 && actions_[a.handover].group == a.group) || dep_done(a.handover));
}

void Adg::run_group(int id)
{
  for (int m : group_of(id)) actions_[m].state = State::Running;
}

void Adg::start_following(int id)
{
  if (!released_following(id))
    throw std::logic_error("Adg::start_following: action " + std::to_string(id) + " is not released");
  run_group(id);
}

bool Adg::group_done(int g) const
{
  for (int m : groups_[g])
    if (actions_[m].state != State::Done) return false;
  return true;
}

std::vector<int> Adg::group_of(int id) const
{
  const int g = actions_[id].group;
  return g < 0 ? std::vector<int>{id} : groups_[g];
}

void Adg::start(int id)
{
  if (!released(id)) throw std::logic_error("Adg::start: action " + std::to_string(id) + " is not released");
  run_group(id);
}

void Adg::resume(int id)
{
  if (actions_[id].state != State::Pending) throw std::logic_error("Adg::resume: action " + std::to_string(id) + " is not pending");
  run_group(id);
}

void Adg::finish(int id)
{
  Action& a = actions_[id];
  if (a.state != State::Running) throw std::logic_error("Adg::finish: action " + std::to_string(id) + " is not running");
  a.state = State::Done;
  at_[a.agent] = a.to;
  ++head_[a.agent];
  ++done_count_;
}

int Adg::chain_candidate(int agent) const
{
  const auto& q = queue_[agent];
  return head_[agent] + 1 < q.size() ? q[head_[agent] + 1] : -1;
}

bool Adg::chainable(int id) const
{
  const Action& a = actions_[id];
  return a.state == State::Pending && a.group < 0 && a.prev >= 0 && actions_[a.prev].state == State::Running &&
         actions_[a.prev].group < 0 && dep_done(a.handover);
}

void Adg::start_chained(int id)
{
  if (!chainable(id)) throw std::logic_error("Adg::start_chained: action " + std::to_string(id) + " is not chainable");
  actions_[id].state = State::Running;
}

int Adg::undone(int agent, size_t k) const
{
  const auto& q = queue_[agent];
  return head_[agent] + k < q.size() ? q[head_[agent] + k] : -1;
}

bool Adg::chainable_following(int id) const
{
  const Action& a = actions_[id];
  return a.state == State::Pending && a.group < 0 && a.prev >= 0 && actions_[a.prev].state == State::Running &&
         actions_[a.prev].group < 0 && (a.handover < 0 || actions_[a.handover].state != State::Pending);
}

void Adg::start_chained_following(int id)
{
  if (!chainable_following(id))
    throw std::logic_error("Adg::start_chained_following: action " + std::to_string(id) + " is not chainable");
  actions_[id].state = State::Running;
}

long long Adg::progress(int agent) const
{
  const int id = next_action(agent);
  return id < 0 ? steps_ : actions_[id].step;
}

long long Adg::min_progress() const
{
  long long p = steps_;
  for (int i = 0; i < num_agents(); ++i) p = std::min(p, progress(i));
  return p;
}

}  // namespace executor
