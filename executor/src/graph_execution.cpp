#include "executor/graph_execution.hpp"

#include <algorithm>

namespace executor {

std::string check(const ExecOptions& o)
{
  if (o.mode != "adg" && o.mode != "adg-follow" && o.mode != "lockstep")
    return "executor: '" + o.mode + "' is not adg, adg-follow or lockstep";
  if (o.window < 1) return "window: " + std::to_string(o.window) + " is not >= 1";
  return "";
}

GraphExecution::GraphExecution(planner::RealtimePlanner& p, const DelaySpec& d, const ExecOptions& o)
    : p_(p), o_(o), delays_(d, static_cast<int>(p.current().size())),
      adg_(std::make_unique<Adg>(p.current())), left_(p.current().size(), 0), pos_(p.current())
{
}

bool GraphExecution::finished() const { return p_.at_goal() && idle(); }

bool GraphExecution::can_accept() const
{
  if (o_.mode == "lockstep") return pending_.empty();  // one configuration at a time, all together
  return adg_->steps() - adg_->min_progress() < o_.window;
}

void GraphExecution::push(const planner::Config& next)
{
  ++st_.commits;
  if (o_.mode == "lockstep") {
    pending_ = next;
    lock_done_ = 0;
    return;
  }
  adg_->append(next);
}

void GraphExecution::top_up(const CommitHook& on_commit)
{
  while (can_accept() && !p_.at_goal()) {
    const planner::Config next = p_.next();
    if (next == p_.current()) break;  // nothing found beyond the root yet: search on
    if (on_commit) on_commit(p_.current(), next);
    p_.commit();
    push(next);
  }
}

void GraphExecution::tick(const planner::Budget& b)
{
  p_.search(b);
  top_up();
  step();
}

void GraphExecution::step()
{
  delays_.tick(st_.ticks);
  if (o_.mode == "lockstep")
    tick_lockstep();
  else
    tick_adg();
  ++st_.ticks;
  st_.delay_ticks = delays_.stop_ticks();
}

void GraphExecution::tick_adg()
{
  const int n = adg_->num_agents();
  // Starts first, on the dependency states of the tick's beginning.
  for (int i = 0; i < n; ++i) {
    const int id = adg_->next_action(i);
    if (id < 0 || adg_->action(id).state != State::Pending) continue;
    const bool follow = o_.mode == "adg-follow";
    if (follow ? !adg_->released_following(id) : !adg_->released(id)) {
      if (!delays_.stopped(i)) ++st_.dependency_waits;
      continue;
    }
    const std::vector<int> group = adg_->group_of(id);
    bool go = true;
    for (int m : group) go = go && !delays_.stopped(adg_->action(m).agent);
    if (!go) continue;
    if (follow)
      adg_->start_following(id);
    else
      adg_->start(id);
    // A rotation moves as one: at its slowest member's pace, held by any stopped member.
    int ticks = 1;
    for (int m : group) ticks = std::max(ticks, delays_.move_ticks(adg_->action(m).agent));
    for (int m : group) left_[adg_->action(m).agent] = ticks;
  }
  for (int i = 0; i < n; ++i) {
    const int id = adg_->next_action(i);
    if (id < 0 || adg_->action(id).state != State::Running) continue;
    bool held = false;
    for (int m : adg_->group_of(id)) held = held || delays_.stopped(adg_->action(m).agent);
    if (held) continue;
    if (left_[i] > 0) --left_[i];
  }
  // Arrivals (travel done); a follower arrives only after its leader (adg-follow): repeat
  // until no more arrive, so a train that moved together arrives in the same tick.
  for (bool any = true; any;) {
    any = false;
    for (int i = 0; i < n; ++i) {
      const int id = adg_->next_action(i);
      if (id < 0 || adg_->action(id).state != State::Running || left_[i] > 0 || !adg_->may_finish(id)) continue;
      adg_->finish(id);
      pos_[i] = adg_->action(id).to;
      ++st_.moves;
      any = true;
    }
  }
}

void GraphExecution::tick_lockstep()
{
  if (pending_.empty()) return;  // nothing committed
  const int n = static_cast<int>(pos_.size());
  bool held = false;
  int need = 1;
  for (int i = 0; i < n; ++i) {
    if (pending_[i] == pos_[i]) continue;
    held = held || delays_.stopped(i);
    need = std::max(need, delays_.move_ticks(i));
  }
  if (held) {
    for (int i = 0; i < n; ++i) st_.lockstep_waits += pending_[i] != pos_[i] && !delays_.stopped(i);
    return;
  }
  if (++lock_done_ < need) return;
  for (int i = 0; i < n; ++i) st_.moves += pending_[i] != pos_[i];
  pos_ = pending_;
  pending_.clear();
  lock_done_ = 0;
}

}  // namespace executor
