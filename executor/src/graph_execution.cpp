#include "executor/graph_execution.hpp"

#include <algorithm>

#include "planner/heading.hpp"

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
      adg_(std::make_unique<Adg>(p.current())), left_(p.current().size(), 0), pos_(p.current()), rot_(p.rotation())
{
  if (rot_) {
    g_ = &rot_->dist().graph();
    heading_ = plan_heading_ = rot_->headings();
    turn_done_.assign(pos_.size(), 0);
    actions_.assign(pos_.size(), 'W');
  }
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
    if (rot_) plan_heading_ = pending_heading_ = rot_->headings();
    return;
  }
  adg_->append(next);
  if (rot_) plan_heading_ = rot_->headings();  // after the commit: the heading at `next`
}

void GraphExecution::top_up(const CommitHook& on_commit)
{
  while (can_accept() && !p_.at_goal()) {
    const planner::Config next = p_.next();
    // Nothing found beyond the root yet: search on. (A rotation step of turns only is a step.)
    if (!rot_ && next == p_.current()) break;
    if (on_commit) on_commit(p_.current(), next);
    p_.commit();
    push(next);
    if (rot_) break;  // one planned step per search
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
  if (rot_) std::fill(actions_.begin(), actions_.end(), 'W');
  if (o_.mode == "lockstep")
    tick_lockstep();
  else
    tick_adg();
  ++st_.ticks;
  st_.delay_ticks = delays_.stop_ticks();
}

int GraphExecution::wanted_heading(int i) const
{
  const int id = adg_->next_action(i);
  if (id < 0) return plan_heading_[i];
  return planner::heading_of_move(*g_, adg_->action(id).from, adg_->action(id).to);
}

bool GraphExecution::turn(int i)
{
  const int want = wanted_heading(i);
  if (heading_[i] == want) {
    turn_done_[i] = 0;
    return false;
  }
  if (delays_.stopped(i)) return true;  // it would turn: it does not move either
  ++st_.turn_ticks;
  if (++turn_done_[i] < delays_.move_ticks(i)) return true;
  turn_done_[i] = 0;
  actions_[i] = planner::turn_toward(heading_[i], want);
  heading_[i] = planner::heading_after(heading_[i], actions_[i]);
  return true;
}

void GraphExecution::tick_adg()
{
  const int n = adg_->num_agents();
  // Headings: a robot that turns (or has to) this tick does not start a move in it.
  std::vector<char> turning(rot_ ? n : 0, 0);
  for (int i = 0; rot_ && i < n; ++i) {
    const int id = adg_->next_action(i);
    if (id < 0 || adg_->action(id).state != State::Running) turning[i] = turn(i);
  }
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
    for (int m : group) go = go && !delays_.stopped(adg_->action(m).agent) && !(rot_ && turning[adg_->action(m).agent]);
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
      if (rot_) actions_[i] = 'F';
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
    // A turn is an action too: it takes a move's time and a stop holds it.
    if (pending_[i] == pos_[i] && !(rot_ && pending_heading_[i] != heading_[i])) continue;
    held = held || delays_.stopped(i);
    need = std::max(need, delays_.move_ticks(i));
  }
  if (held) {
    for (int i = 0; i < n; ++i) st_.lockstep_waits += pending_[i] != pos_[i] && !delays_.stopped(i);
    return;
  }
  if (++lock_done_ < need) return;
  for (int i = 0; i < n; ++i) st_.moves += pending_[i] != pos_[i];
  for (int i = 0; rot_ && i < n; ++i) {
    if (pending_[i] != pos_[i])
      actions_[i] = 'F';
    else if (pending_heading_[i] != heading_[i])
      actions_[i] = planner::turn_toward(heading_[i], pending_heading_[i]);
    st_.turn_ticks += need * (pending_heading_[i] != heading_[i]);
  }
  if (rot_) heading_ = pending_heading_;
  pos_ = pending_;
  pending_.clear();
  lock_done_ = 0;
}

}  // namespace executor
