// Switchable ADG, greedy form: see Adg::try_switch in adg.hpp.
#include <algorithm>
#include <vector>

#include "executor/adg.hpp"

namespace executor {

// Whether `target` is reachable from `from` over dependency edges (prev, handover; a group
// member's group mates, since a group starts as one). Done actions end the search: what
// depends only on done actions can run, so no cycle passes through them.
bool Adg::depends_on(int from, int target) const
{
  std::vector<int> stack{from};
  std::vector<char> seen(actions_.size(), 0);
  while (!stack.empty()) {
    const int x = stack.back();
    stack.pop_back();
    if (x < base_ || act(x).state == State::Done) continue;
    if (x == target) return true;
    if (seen[x - base_]) continue;
    seen[x - base_] = 1;
    const Action& a = act(x);
    if (a.prev >= 0) stack.push_back(a.prev);
    if (a.handover >= 0) stack.push_back(a.handover);
    if (a.group >= 0)
      for (int m : group(a.group))
        if (m != x) stack.push_back(m);
  }
  return false;
}

bool Adg::try_switch(int id, const SwitchRule& rule)
{
  if (id < base_ || id >= num_actions()) return false;
  Action& ej = act(id);  // j enters v
  const int h = ej.handover;  // i leaves v
  if (ej.state != State::Pending || ej.group >= 0 || h < base_) return false;
  const Action& hi = act(h);
  if (hi.state != State::Pending || hi.group >= 0) return false;
  const int e_i = hi.prev;  // i enters v (-1: i stands on v already)
  if (e_i < base_) return false;
  Action& ei = act(e_i);
  if (ei.state != State::Pending || ei.group >= 0 || ei.to != ej.to) return false;
  if (released(e_i) || released_following(e_i)) return false;  // i is about to enter v: keep the plan's order
  // i passes v only once before j (an earlier pass of its own would have no hand-over edge
  // for j to take over).
  {
    const auto& qi = queue_[ei.agent];
    size_t k = head_[ei.agent];
    for (; k < qi.size() && qi[k] < e_i; ++k)
      if (act(qi[k]).from == ej.to || act(qi[k]).to == ej.to) return false;
    if (static_cast<int>(k - head_[ei.agent]) < rule.lead) return false;  // i is near: keep the order
    if (rule.leader_at_rest && act(qi[head_[ei.agent]]).state != State::Pending) return false;  // i is on its way: keep the order
  }
  // j's leave of v: the next action in j's queue after id.
  const auto& q = queue_[ej.agent];
  const auto it = std::lower_bound(q.begin() + static_cast<std::ptrdiff_t>(head_[ej.agent]), q.end(), id);
  if (it == q.end() || it + 1 == q.end()) return false;  // j stays on v within the lookahead
  const int l_j = *(it + 1);
  if (act(l_j).group >= 0) return false;
  // j must pass, not park: the cell after v has begun to be left (or needs no hand-over), so
  // j will not hold v while i arrives.
  if (rule.must_pass && act(l_j).handover >= base_ && act(act(l_j).handover).state == State::Pending) return false;
  // The next occupant of v after j: the entry whose hand-over is j's leave, or else j's own
  // next entry into v (a re-entry has no hand-over, yet after the switch it must wait for
  // i's leave). Not by id order: earlier switches reorder the cell.
  int n_id = -1;
  for (int x = base_; x < num_actions() && n_id < 0; ++x)
    if (act(x).handover == l_j) n_id = x;
  for (auto k = it + 2; k != q.end() && n_id < 0; ++k)
    if (act(*k).to == ej.to) n_id = *k;
  if (n_id >= 0 && act(n_id).group >= 0) return false;
  const int v = ej.to;
  // Switch: P -> i -> j -> N on v becomes P -> j -> i -> N.
  const int p = ei.handover;
  const int old_ej = ej.handover, old_ei = ei.handover, old_n = n_id >= 0 ? act(n_id).handover : -1;
  ej.handover = (p >= base_ && act(p).agent != ej.agent) ? p : -1;
  ei.handover = l_j;
  if (n_id >= 0) act(n_id).handover = act(n_id).agent != hi.agent ? h : -1;
  // A new cycle would pass through a new edge a -> b (a depends on b): b depends on a.
  if ((ej.handover >= 0 && depends_on(ej.handover, id)) || depends_on(l_j, e_i) ||
      (n_id >= 0 && act(n_id).handover >= 0 && depends_on(h, n_id))) {
    ej.handover = old_ej;
    ei.handover = old_ei;
    if (n_id >= 0) act(n_id).handover = old_n;
    return false;
  }
  if (static_cast<size_t>(v) < last_leave_.size() && last_leave_[v] == l_j) last_leave_[v] = h;
  ++switches_;
  return true;
}

}  // namespace executor
