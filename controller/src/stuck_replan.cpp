// StuckWatch (stuck_replan.hpp) and Run's replan around stuck AGVs.
#include "stuck_replan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "controller/sumo_error.hpp"
#include "run.hpp"
#include "tasks/lifelong_goal.hpp"

namespace controller {

StuckWatch::StuckWatch(int n, double stuck_after_s, double dt, bool learn)
    : n_(n), after_s_(stuck_after_s), dt_(dt), learn_(learn), stall_s_(n, 0.0), last_(n), immobile_(n, 0), target_(n, 0)
{
}

bool StuckWatch::observe(const executor::Adg& adg, const std::vector<VehiclePose>& poses,
                         const executor::DelayModel& delays, const std::vector<int>& gated)
{
  // Who holds somebody up: the owner of an undone hand-over another AGV's next move waits on.
  std::vector<uint8_t> blocks(n_, 0);
  for (int j = 0; j < n_; ++j) {
    const int id = adg.next_action(j);
    // (adg-follow: also a running move that follows an owner still leaving its cell)
    if (id < 0 || adg.action(id).handover < 0) continue;
    const executor::Action& h = adg.action(adg.action(id).handover);
    if (h.state != executor::State::Done) blocks[h.agent] = 1;
  }
  target_ = immobile_;
  for (int i = 0; i < n_; ++i) {
    const bool moved = poses[i].lane != last_[i].lane || std::abs(poses[i].pos - last_[i].pos) > 1e-9;
    last_[i] = poses[i];
    const int id = adg.next_action(i);
    // Running with its cell handed over (adg-follow: not just following a leader that is still
    // leaving it -- that one waits on the leader, which is watched itself), or released.
    const bool may_go = id >= 0 && (adg.may_finish(id) || adg.released(id)) && gated[i] < 0;
    // A stall that ended by itself (moved on, never immobile) while it held somebody up: a
    // passing stop of this fleet. (Not one that held nobody up: it was never a candidate, and
    // an AGV broken down for a minute in nobody's way must not teach that a minute passes.)
    if (moved && !immobile_[i] && blocks[i]) longest_free_ = std::max(longest_free_, stall_s_[i]);
    stall_s_[i] = may_go && !moved ? stall_s_[i] + dt_ : 0.0;
    if (immobile_[i] && !delays.stopped(i)) target_[i] = 0;  // it reports itself ready again
    if (!immobile_[i] && stall_s_[i] >= threshold_s() - 1e-9 && blocks[i]) target_[i] = 1;
  }
  return target_ != immobile_;
}

std::vector<int> StuckWatch::running(const executor::Adg& adg, int i)
{
  std::vector<int> out;
  for (size_t k = 0;; ++k) {  // the Driver chains as many as it may need to brake (driver.cpp)
    const int id = adg.undone(i, k);
    if (id < 0 || adg.action(id).state != executor::State::Running) break;
    out.push_back(id);
  }
  return out;
}

long long StuckWatch::min_progress(const executor::Adg& adg) const
{
  long long p = adg.steps();
  for (int i = 0; i < n_; ++i)
    if (!immobile_[i]) p = std::min(p, adg.progress(i));
  return p;
}

void StuckWatch::replanned()
{
  for (int i = 0; i < n_; ++i) stuck_events_ += target_[i] && !immobile_[i];
  immobile_ = target_;
  std::fill(stall_s_.begin(), stall_s_.end(), 0.0);
}

std::string StuckWatch::describe() const
{
  std::string s;
  for (int i = 0; i < n_; ++i) {
    if (target_[i] == immobile_[i]) continue;
    s += (s.empty() ? "" : ", ") + std::string("agv") + std::to_string(i) + (target_[i] ? " immobile" : " mobile again");
  }
  return s;
}

// The replan itself: a new planner and ADG from where the AGVs are and are driving to.
void Run::replan(executor::Adg& adg, Driver& drv, const std::vector<uint8_t>& immobile, bool regraph)
{
  const int n = ins_.num_agents();
  planner::Config at(n);
  for (int i = 0; i < n; ++i) at[i] = adg.at(i);

  // The committed plan from the ADG's start on, each agent's path cut at its progress p_i
  // (C'_t[i] = C_min(t, p_i)[i]; a move in progress is not done: cut before it): still
  // valid, because the ADG let no agent past a cell hand-over whose other side is not done
  // -- an agent that entered v at a step <= p_i did so after v's previous occupant had left
  // it, and a later occupant of v would wait for it to leave, which it has not: no two
  // agents share a vertex in any C'_t.
  const size_t base = c_.plan_.size() - 1 - static_cast<size_t>(adg.steps());
  long long last = 0, first = adg.steps();
  std::vector<long long> prog(n);
  for (int i = 0; i < n; ++i) last = std::max(last, prog[i] = adg.progress(i)), first = std::min(first, prog[i]);
  // Steps up to the slowest AGV's progress are unchanged (so are those before the oldest
  // kept one): only the last window's steps are rewritten, whatever the run's length.
  const long long t0 = std::max(first, c_.plan_.first() > base ? static_cast<long long>(c_.plan_.first() - base) : 0);
  for (long long t = t0; t <= last; ++t)
    for (int i = 0; i < n; ++i) c_.plan_.at(base + t)[i] = c_.plan_.at(base + std::min(t, prog[i]))[i];
  c_.plan_.resize(base + static_cast<size_t>(last) + 1);
  if (c_.plan_.back() != at) throw ControlError("replan: the executed configuration is not where the ADG says");

  // The moves in progress (stuck_replan.hpp), as steps: an AGV's k-th running move comes
  // after its (k-1)-th, and never before the move that hands its target over (the same step
  // is a train; a rotation group is one step). Under adg-follow a follower may run its
  // 2nd move into a cell whose occupant runs its 3rd move out of it: by index alone the
  // follower would arrive a step early (a vertex conflict in the cut plan).
  std::vector<std::vector<int>> mid(n);  // per agent: its running actions (old ADG)
  for (int i = 0; i < n; ++i) mid[i] = StuckWatch::running(adg, i);
  std::vector<std::vector<int>> level(n);
  auto level_of = [&](int id) {  // of a running action, 0 if done / not running
    const int j = adg.action(id).agent;
    for (size_t k = 0; k < mid[j].size(); ++k)
      if (mid[j][k] == id) return level[j].empty() ? 0 : level[j][k];
    return 0;
  };
  for (int i = 0; i < n; ++i) level[i].assign(mid[i].size(), 1);
  for (bool changed = true; changed;) {  // longest paths in a DAG (+ groups): terminates
    changed = false;
    for (int i = 0; i < n; ++i)
      for (size_t k = 0; k < mid[i].size(); ++k) {
        const executor::Action& a = adg.action(mid[i][k]);
        int l = k ? level[i][k - 1] + 1 : 1;
        if (a.handover >= 0) l = std::max(l, level_of(a.handover));
        if (a.group >= 0)
          for (int m : adg.group_of(mid[i][k])) l = std::max(l, level_of(m));
        if (l > level[i][k]) level[i][k] = l, changed = true;
      }
  }
  int levels = 0;
  for (int i = 0; i < n; ++i)
    if (!level[i].empty()) levels = std::max(levels, level[i].back());
  std::vector<planner::Config> steps;  // at -> ... -> from
  planner::Config from = at;
  for (int t = 1; t <= levels; ++t) {
    for (int i = 0; i < n; ++i)
      for (size_t k = 0; k < mid[i].size(); ++k)
        if (level[i][k] == t) from[i] = adg.action(mid[i][k]).to;
    steps.push_back(from);
    c_.plan_.push_back(from);
  }

  if (plan_mode()) plan_debts(prog, steps);
  const planner::Config goals = !tm_ ? ins_.goals : plan_mode() ? plan_goals() : tm_->goals();
  // The cut plan from the last final configuration on (settle(): everything before it was
  // checked and stays): the validator there, then the rewritten steps.
  val_ = std::make_unique<planner::Validator>(*val_final_);
  val_->set_goals(goals);
  for (size_t t = val_final_at_ + 1; t < c_.plan_.size(); ++t)
    if (!val_->step(c_.plan_.at(t))) throw ControlError("replan: the cut plan is invalid: " + val_->error());

  // The planner restarted from there, the stuck ones immobile, in one restart (a fresh
  // planner where it cannot, on the old one's distance tables). No search here: the next
  // step's search() has what is left of the step's budget, none if this used it (Run::step).
  planner::GoalTest test = tm_ ? tasks::lifelong_goal_test(*tm_, from) : planner::GoalTest{};
  if (regraph) {
    // The rules' new graph (rules.hpp), built from where the moves in progress end: AGVs
    // whose moves end on cells just closed leave them by the evacuation arcs.
    // Zones blocked as Run::rules_tick_adg sees them (where the ADG has the AGVs: one whose
    // move out of a zone runs still holds it), so the next tick compares like with like.
    zone_occ_ = cfg_.rules.enforce_zones ? rules_->blocked_zones(at) : std::vector<uint8_t>(rules_->zones().size(), 0);
    // Frozen (watched lanes SUMO closed): the lane each AGV's front is on when its moves in
    // progress end -- the Commander's pose is the last running move's target.
    std::vector<std::string> lanes(n);
    for (int i = 0; i < n; ++i) lanes[i] = cmd_->pose(i).lane;
    auto rg = std::make_unique<planner::Graph>(
        rules_->graph(zone_occ_, cfg_.rules.enforce_closures, rules_->frozen_cells(from, lanes)));
    const planner::Config eff = rule_goals(*rg, from);
    replan_expansions_ += p_->expansions();
    // Rotation solvers: each AGV's heading where its moves in progress end -- that of its
    // last running move, else the one the Driver has turned it to (a turn under way
    // finishes there) -- not the planner's, which ran ahead of the cut.
    std::vector<int> headings;
    if (p_->rotation())
      for (int i = 0; i < n; ++i)
        headings.push_back(mid[i].empty() ? cmd_->heading(i)
                                          : cmd_->move_heading(adg.action(mid[i].back()).from, adg.action(mid[i].back()).to));
    // The old planner goes first (it still refers to the old graph), then the old graph.
    p_ = make_planner(cfg_.planner, *rg, from, eff, pref_.get(), std::move(test), headings, nullptr, plan_zones_);
    rules_graph_ = std::move(rg);
    cap_dist_tables();
    if (std::find(immobile.begin(), immobile.end(), 1) != immobile.end()) p_->set_immobile(immobile);
    ++m_.rules.replans;
  } else {
    // With rules the planner stays on their graph, with the goals it can reach there.
    const planner::Config eff = rules_graph_ ? rule_goals(*rules_graph_, from) : goals;
    if (!p_->restart_at(from, eff, test, immobile)) {
      replan_expansions_ += p_->expansions();
      p_ = make_planner(cfg_.planner, rules_graph_ ? *rules_graph_ : c_.map_.graph, from, eff, pref_.get(),
                        std::move(test), {}, rules_graph_ ? nullptr : dist_cache_, plan_zones_);
      if (tm_) p_->set_max_dist_tables(2 * from.size() + 256);
      p_->set_immobile(immobile);  // one restart for all (realtime_planner.hpp)
    }
  }
  // Moves in progress cannot stop on a cell boundary: a cell closed under one is no entry
  // into a closed cell for RuleCheck (rule_check.hpp).
  if (regraph && rule_check_)
    for (int i = 0; i < n; ++i) {
      std::vector<planner::Vertex> cells;
      for (int id : mid[i]) cells.push_back(adg.action(id).to);
      rule_check_->excuse(i, std::move(cells));
    }
  adg = executor::Adg(at);
  for (const planner::Config& c : steps) adg.append(c);
  if (oab_) oab_->reset(adg.tail());  // the old planner's commits held back: gone with it
  for (int i = 0; i < n; ++i) {
    if (mid[i].empty()) continue;
    std::vector<int> ids;
    for (size_t k = 0; k < mid[i].size(); ++k) {
      ids.push_back(adg.undone(i, k));
      // Released by the replaced ADG (strict or following rule): carried over as running.
      if (adg.action(ids.back()).state == executor::State::Pending) adg.resume(ids.back());  // a group as one
    }
    drv.renumber(i, ids);
  }
  if (!regraph) ++m_.replans;
}

void Run::settle(size_t t)
{
  if (val_final_)
    for (; val_final_at_ + 1 < t; ++val_final_at_)
      if (!val_final_->step(c_.plan_.at(val_final_at_ + 1)))
        throw ControlError("settled plan step " + std::to_string(val_final_at_ + 1) + " is invalid: " + val_final_->error());
  c_.plan_.settle(t);
}

void Run::stuck_step(executor::Adg& adg, Driver& drv)
{
  if (stuck_ && stuck_->observe(adg, last_poses_, *delays_, drv.gated())) {
    if (cfg_.run.progress_s > 0)
      std::fprintf(stderr, "[rtlacam-sumo] t=%.1f s: replan (%s)\n", sumo_->time(), stuck_->describe().c_str());
    // Only recoveries: the committed plan keeps them in place, which stays valid -- the
    // planner just searches on from its current configuration with them mobile.
    bool adds = false;
    for (int i = 0; i < ins_.num_agents(); ++i) adds = adds || (stuck_->target()[i] && !stuck_->immobile()[i]);
    if (adds) {
      replan(adg, drv, stuck_->target());
    } else {
      p_->set_immobile(stuck_->target());  // the recovered ones mobile, in one restart
      ++m_.replans;
    }
    stuck_->replanned();
  }
  if (stuck_) m_.stuck_events = stuck_->stuck_events();
  // When each AGV got to its goal for good (one-shot): the tests' "others finish first".
  if (!tm_) {
    m_.goal_s.resize(adg.num_agents(), -1);
    for (int i = 0; i < adg.num_agents(); ++i) {
      if (adg.at(i) != ins_.goals[i]) m_.goal_s[i] = -1;
      else if (m_.goal_s[i] < 0) m_.goal_s[i] = sumo_->time();
    }
  }
}

}  // namespace controller
