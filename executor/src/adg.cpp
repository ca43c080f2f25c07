#include "executor/adg.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace executor {

Adg::Adg(const planner::Config& start, int compact_min)
    : tail_(start), at_(start), queue_(start.size()), head_(start.size(), 0), compact_min_(compact_min)
{
}

int Adg::append(const planner::Config& next)
{
  if (next.size() != tail_.size()) throw std::invalid_argument("Adg::append: configuration of the wrong size");
  compact();
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
  for (int id = first; id < last; ++id) last_leave_[act(id).from] = id;
  for (int id = first; id < last; ++id) {
    Action& a = act(id);
    const int h = last_leave_[a.to];
    if (h >= 0 && act(h).agent != a.agent) a.handover = h;
  }

  // Rotation cycles within this step: following same-step hand-overs from an action
  // returns to it. Each action has at most one hand-over, so walking finds each cycle.
  for (int id = first; id < last; ++id) {
    if (act(id).group >= 0) continue;
    std::vector<int> path;
    int x = id;
    while (x >= first && act(x).group < 0 && std::find(path.begin(), path.end(), x) == path.end()) {
      path.push_back(x);
      x = act(x).handover;
    }
    if (x < first || act(x).group >= 0) continue;  // (x < first: also -1, a dropped leave)
    auto it = std::find(path.begin(), path.end(), x);
    const int g = group_base_ + static_cast<int>(groups_.size());
    groups_.emplace_back(it, path.end());
    for (int m : groups_.back()) act(m).group = g;
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
  const int p = act(id).prev;
  if (p < 0) return true;
  if (act(p).group < 0) return dep_done(p);
  for (int m : group(act(p).group))
    if (act(m).state != State::Done) return false;
  return true;
}

bool Adg::outside_deps_done(int id) const
{
  const Action& a = act(id);
  if (!prev_done(id)) return false;
  if (a.handover >= 0 && !(a.group >= 0 && act(a.handover).group == a.group) && !dep_done(a.handover)) return false;
  return true;
}

bool Adg::released(int id) const
{
  const Action& a = act(id);
  if (a.state != State::Pending) return false;
  if (a.group < 0) return outside_deps_done(id);
  for (int m : group(a.group))
    if (act(m).state != State::Pending || !outside_deps_done(m)) return false;
  return true;
}

bool Adg::outside_deps_started(int id) const
{
  const Action& a = act(id);
  if (!prev_done(id)) return false;
  if (a.handover >= 0 && !(a.group >= 0 && act(a.handover).group == a.group) &&
      act(a.handover).state == State::Pending)
    return false;
  return true;
}

bool Adg::released_following(int id) const
{
  const Action& a = act(id);
  if (a.state != State::Pending) return false;
  if (a.group < 0) return outside_deps_started(id);
  for (int m : group(a.group))
    if (act(m).state != State::Pending || !outside_deps_started(m)) return false;
  return true;
}

bool Adg::may_finish(int id) const
{
  const Action& a = act(id);
  return a.state == State::Running &&
         (a.handover < 0 || (a.group >= 0 && act(a.handover).group == a.group) || dep_done(a.handover));
}

void Adg::run_group(int id)
{
  for (int m : group_of(id)) act(m).state = State::Running;
}

void Adg::start_following(int id)
{
  if (!released_following(id))
    throw std::logic_error("Adg::start_following: action " + std::to_string(id) + " is not released");
  run_group(id);
}

bool Adg::group_done(int g) const
{
  for (int m : group(g))
    if (act(m).state != State::Done) return false;
  return true;
}

std::vector<int> Adg::group_of(int id) const
{
  const int g = act(id).group;
  return g < 0 ? std::vector<int>{id} : group(g);
}

void Adg::start(int id)
{
  if (!released(id)) throw std::logic_error("Adg::start: action " + std::to_string(id) + " is not released");
  run_group(id);
}

void Adg::resume(int id)
{
  if (act(id).state != State::Pending) throw std::logic_error("Adg::resume: action " + std::to_string(id) + " is not pending");
  run_group(id);
}

void Adg::finish(int id)
{
  Action& a = act(id);
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
  const Action& a = act(id);
  return a.state == State::Pending && a.group < 0 && a.prev >= 0 && act(a.prev).state == State::Running &&
         act(a.prev).group < 0 && dep_done(a.handover);
}

void Adg::start_chained(int id)
{
  if (!chainable(id)) throw std::logic_error("Adg::start_chained: action " + std::to_string(id) + " is not chainable");
  act(id).state = State::Running;
}

int Adg::undone(int agent, size_t k) const
{
  const auto& q = queue_[agent];
  return head_[agent] + k < q.size() ? q[head_[agent] + k] : -1;
}

bool Adg::chainable_following(int id) const
{
  const Action& a = act(id);
  return a.state == State::Pending && a.group < 0 && a.prev >= 0 && act(a.prev).state == State::Running &&
         act(a.prev).group < 0 && (a.handover < 0 || act(a.handover).state != State::Pending);
}

void Adg::start_chained_following(int id)
{
  if (!chainable_following(id))
    throw std::logic_error("Adg::start_chained_following: action " + std::to_string(id) + " is not chainable");
  act(id).state = State::Running;
}

long long Adg::progress(int agent) const
{
  const int id = next_action(agent);
  return id < 0 ? steps_ : act(id).step;
}

long long Adg::min_progress() const
{
  long long p = steps_;
  for (int i = 0; i < num_agents(); ++i) p = std::min(p, progress(i));
  return p;
}

void Adg::compact()
{
  // First undone action of any agent; everything before it is done.
  int k = num_actions();
  for (int i = 0; i < num_agents(); ++i) {
    const int id = next_action(i);
    if (id >= 0) k = std::min(k, id);
  }
  // Back to the start of its plan step: rotation groups live within one step.
  while (k > base_ && k < num_actions() && act(k - 1).step == act(k).step) --k;
  const int drop = k - base_;
  if (drop < compact_min_ || drop < stored_actions() / 2) return;
  for (Action& a : actions_) {
    if (a.prev >= 0 && a.prev < k) a.prev = -1;
    if (a.handover >= 0 && a.handover < k) a.handover = -1;
  }
  for (int& l : last_leave_)
    if (l >= 0 && l < k) l = -1;
  // Groups are made in id order: drop those whose members all went.
  size_t g = 0;
  while (g < groups_.size() && groups_[g].front() < k) ++g;
  groups_.erase(groups_.begin(), groups_.begin() + static_cast<std::ptrdiff_t>(g));
  group_base_ += static_cast<int>(g);
  for (size_t i = 0; i < queue_.size(); ++i) {
    auto& q = queue_[i];
    const auto cut = std::lower_bound(q.begin(), q.end(), k);
    head_[i] -= static_cast<size_t>(cut - q.begin());
    q.erase(q.begin(), cut);
  }
  actions_.erase(actions_.begin(), actions_.begin() + drop);
  actions_.shrink_to_fit();
  base_ = k;
}

}  // namespace executor
