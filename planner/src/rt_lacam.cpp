#include "planner/rt_lacam.hpp"

namespace planner {

RtLacam::RtLacam(const Graph& g, const Config& starts, const Config& goals, LacamOptions opt, ActionPreference* pref,
                 GoalTest test)
    : dist_(g), lacam_(g, dist_, opt, pref), current_(starts), keep_priorities_(opt.keep_priorities)
{
  set_goals(goals, std::move(test));
}

void RtLacam::set_goals(const Config& goals, GoalTest test)
{
  test_ = test;
  // A new epoch may keep the agents' PIBT priorities (LacamOptions::keep_priorities).
  const HNode* root = lacam_.root();
  if (keep_priorities_ && root && goals.size() == current_.size()) {
    carried_.assign(root->priorities, root->priorities + lacam_.num_agents());
    lacam_.reset(current_, goals, std::move(test), carried_.data());
  } else {
    lacam_.reset(current_, goals, std::move(test));
  }
  planned_ = promised_ = nullptr;
}

Status RtLacam::search(const Budget& b)
{
  if (lacam_.status() != Status::Searching && !lacam_.refining()) return lacam_.status();
  planned_ = nullptr;
  return lacam_.search(b);
}

const HNode* RtLacam::planned()
{
  if (planned_) return planned_;
  const HNode* target = lacam_.goal_node() ? lacam_.goal_node() : lacam_.top();
  return planned_ = lacam_.next_toward(target);
}

const Config& RtLacam::next()
{
  const HNode* h = promised_ = planned();
  next_.assign(h->C, h->C + lacam_.num_agents());
  return next_;
}

void RtLacam::commit()
{
  const HNode* h = promised_ ? promised_ : planned();
  promised_ = nullptr;
  if (h == lacam_.root()) return;  // wait
  lacam_.reroot(h);
  planned_ = nullptr;
  current_.assign(h->C, h->C + lacam_.num_agents());
}

bool RtLacam::at_goal() const
{
  return passes_goal_test(test_, current_, lacam_.goals());
}

}  // namespace planner
