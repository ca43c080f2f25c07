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
  goal_path_.clear();
  planned_ = promised_ = nullptr;
}

Status RtLacam::search(const Budget& b)
{
  if (lacam_.status() != Status::Searching) return lacam_.status();
  planned_ = nullptr;
  const Status s = lacam_.search(b);
  if (s == Status::Solved)
    for (const HNode* h = lacam_.goal_node(); h; h = h->parent) goal_path_.push_back(h);
  return s;
}

const HNode* RtLacam::planned()
{
  if (planned_) return planned_;
  if (!goal_path_.empty()) return planned_ = goal_path_.size() >= 2 ? goal_path_[goal_path_.size() - 2] : lacam_.root();
  return planned_ = lacam_.next_toward(lacam_.top());
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
  const bool on_goal_path = goal_path_.size() >= 2 && goal_path_[goal_path_.size() - 2] == h;
  lacam_.reroot(h);
  planned_ = nullptr;
  if (on_goal_path) {
    goal_path_.pop_back();
  } else if (!goal_path_.empty()) {
    // The goal was found after next() promised a move off its path: walk it again.
    goal_path_.clear();
    for (const HNode* g = lacam_.goal_node(); g; g = g->parent) goal_path_.push_back(g);
  }
  current_.assign(h->C, h->C + lacam_.num_agents());
}

bool RtLacam::at_goal() const
{
  return passes_goal_test(test_, current_, lacam_.goals());
}

}  // namespace planner
