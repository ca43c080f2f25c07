#include "planner/lacam/rt_lacam.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "planner/lacam/priority.hpp"

namespace planner {

RtLacam::RtLacam(const Graph& g, const Config& starts, const Config& goals, LacamOptions opt, ActionPreference* pref,
                 GoalTest test, std::shared_ptr<DistCache> cache)
    : dist_(g, std::move(cache)),
      lacam_(std::make_unique<Lacam>(g, dist_, opt, pref)),
      current_(starts),
      g_(g),
      opt_(opt),
      pref_(pref)
{
  set_goals(goals, std::move(test));
}

void RtLacam::set_goals(const Config& goals, GoalTest test)
{
  test_ = std::move(test);
  if (immobile_.size() != goals.size()) immobile_.assign(goals.size(), 0);
  restart(goals);
}

void RtLacam::set_immobile(int agent, bool immobile)
{
  check_immobile_agent(agent, immobile_.size());
  if (immobile_[agent] == static_cast<uint8_t>(immobile)) return;
  immobile_[agent] = immobile;
  lacam_->set_immobile(immobile_);
  const Config goals = lacam_->goals();
  restart(goals);
}

void RtLacam::set_immobile(const std::vector<uint8_t>& immobile)
{
  check_marks(immobile, immobile_.size());
  std::vector<uint8_t> marks(immobile.size());
  for (size_t i = 0; i < immobile.size(); ++i) marks[i] = immobile[i] != 0;
  if (marks == immobile_) return;
  immobile_ = std::move(marks);
  lacam_->set_immobile(immobile_);
  const Config goals = lacam_->goals();
  restart(goals);
}

bool RtLacam::restart_at(const Config& at, const Config& goals, GoalTest test, const std::vector<uint8_t>& immobile)
{
  check_restart(at, goals, immobile, current_.size());
  current_ = at;
  test_ = std::move(test);
  for (size_t i = 0; i < immobile.size(); ++i) immobile_[i] = immobile[i] != 0;
  lacam_->set_immobile(immobile_);
  restart(goals);
  return true;
}

void RtLacam::restart(const Config& goals)
{
  GoalTest test = relaxed_goal_test(g_, current_, goals, immobile_, test_);
  // A new epoch may keep the agents' PIBT priorities (LacamOptions::keep_priorities).
  const HNode* root = lacam_->root();
  const int n = static_cast<int>(current_.size());
  const bool keep = opt_.keep_priorities && root && goals.size() == current_.size();
  if (static_cast<int>(hint_.size()) == n && goals.size() == current_.size()) {
    // The task layer's hints raise the root's priorities (priority.hpp, raise_to_hint).
    dist_.set_goals(goals);
    tie_.resize(n);
    init_priorities(current_.data(), n, dist_, tie_.data());
    if (keep) carried_.assign(root->priorities, root->priorities + n);
    else carried_ = tie_;
    raise_to_hint(tie_.data(), hint_, n, carried_.data());
    lacam_->reset(current_, goals, std::move(test), carried_.data());
  } else if (keep) {
    carried_.assign(root->priorities, root->priorities + n);
    carried_order_.assign(root->order, root->order + n);
    lacam_->reset(current_, goals, std::move(test), carried_.data(), carried_order_.data());
  } else {
    lacam_->reset(current_, goals, std::move(test));
  }
  planned_ = promised_ = nullptr;
  drop_ahead();
  epoch_switches_ = 0;
  ++restarts_;
}

Status RtLacam::search(const Budget& b)
{
  const bool held = any_immobile(immobile_);  // a dry relaxed search is no failure
  if (lacam_->status() != Status::Searching && !lacam_->refining()) {
    // The followed search is idle: the iteration's budget goes to the lookahead (header).
    if (ahead_pending_) start_ahead();
    if (ahead_ && (ahead_->status() == Status::Searching || ahead_->refining())) {
      // A tenth of the time is left to this iteration's move: the lookahead does not know
      // the followed search's bookkeeping (measured p99 1.05-1.10 ms at 1 ms without it).
      Budget ab = b;
      ab.ms *= 0.9;
      ahead_->search(ab);
    }
    return held && lacam_->status() == Status::NoSolution ? Status::Searching : lacam_->status();
  }
  planned_ = nullptr;
  const Status s = lacam_->search(b);
  return held && s == Status::NoSolution ? Status::Searching : s;
}

const HNode* RtLacam::planned()
{
  if (planned_) return planned_;
  const HNode* target = lacam_->goal_node() ? lacam_->goal_node() : lacam_->top();
  const HNode* h = lacam_->best_next();  // soc: the followed path (best_path.hpp)
  if (!h) h = lacam_->next_toward(target);
  // Before a goal node is known the agents take only moves they can undo (the header's
  // one-way rule): the old root then hangs under the new one by a legal move and the tree
  // stays one search over the start's configurations. A one-way move waits for the goal.
  if (!lacam_->goal_node() && !lacam_->reversible(lacam_->root(), h)) h = lacam_->root();
  return planned_ = h;
}

const Config& RtLacam::next()
{
  const HNode* h = promised_ = planned();
  next_.assign(h->C, h->C + lacam_->num_agents());
  return next_;
}

void RtLacam::commit()
{
  const HNode* h = promised_ ? promised_ : planned();
  promised_ = nullptr;
  if (h == lacam_->root()) {  // wait
    lacam_->waited();
    planned_ = nullptr;
    return;
  }
  lacam_->reroot(h);
  planned_ = nullptr;
  current_.assign(h->C, h->C + lacam_->num_agents());
  if (g_.directed()) look_ahead();
}

// The lookahead (header, "Directed graphs"): at its configuration, the followed search is
// replaced by it only if its path to a goal is strictly shorter and no dearer; else it is
// dropped. Only the choice is made here: the search itself starts in search(), within the
// iteration's budget.
void RtLacam::look_ahead()
{
  if (ahead_ || ahead_pending_) {
    if (++ahead_steps_ < ahead_k_) return;
    if (ahead_ && current_ == ahead_at_ && ahead_->goal_node()) {
      const int mine = lacam_->best_steps(), theirs = ahead_->best_steps();
      const int64_t mc = lacam_->best_cost(), tc = ahead_->best_cost();
      if (theirs < mine && (mc < 0 || tc < 0 || tc <= mc) && epoch_switches_ < kMaxSwitches) {
        lacam_.swap(ahead_);
        std::swap(main_base_, ahead_base_);
        planned_ = promised_ = nullptr;
        ++switches_, ++epoch_switches_;
      }
    }
    drop_ahead();
  }
  // Only while the followed search is idle (refinement over), with no agent held, and the
  // path long enough for a search from k steps on to be worth its budget.
  if (!opt_.refine || !opt_.lookahead || !lacam_->goal_node() || lacam_->refining() ||
      lacam_->status() == Status::Searching || any_immobile(immobile_))
    return;
  const int steps = lacam_->best_steps();
  const int k = std::min(kAheadMax, std::max(kAheadMin, steps / 4));
  if (steps <= 2 * k) return;
  ahead_at_ = lacam_->best_at(k);
  ahead_k_ = k;
  ahead_steps_ = 0;
  ahead_pending_ = true;
}

void RtLacam::start_ahead()
{
  ahead_pending_ = false;
  // A dropped search is reused: reset() keeps its arenas, where freeing a large tree would
  // cost the move's iteration most of a millisecond (measured: 0.6 ms at N = 400).
  ahead_ = spare_ ? std::move(spare_) : std::make_unique<Lacam>(g_, dist_, opt_, pref_);
  ahead_base_ = ahead_->expansions();
  if (!pockets_.empty()) ahead_->set_pockets(pockets_, pocket_cost_);
  ahead_->reset(ahead_at_, lacam_->goals(), relaxed_goal_test(g_, ahead_at_, lacam_->goals(), immobile_, test_));
  ++lookaheads_;
}

void RtLacam::drop_ahead()
{
  ahead_pending_ = false;
  if (!ahead_) return;
  retired_expansions_ += ahead_->expansions() - ahead_base_;
  if (!spare_) spare_ = std::move(ahead_);
  ahead_.reset();
}

bool RtLacam::at_goal() const
{
  return passes_goal_test(test_, current_, lacam_->goals());
}

}  // namespace planner
