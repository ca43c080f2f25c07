#include "planner/lacam/naive_rt_lacam.hpp"

#include <stdexcept>
#include <string>

#include <algorithm>

#include "planner/lacam/immobile.hpp"

namespace planner {
namespace {

// Naive RT-LaCAM restarts every iteration: nothing to refine, nor to resume.
LacamOptions without_refine(LacamOptions o)
{
  o.refine = false;
  o.resumable = false;
  return o;
}

}  // namespace

NaiveRtLacam::NaiveRtLacam(const Graph& g, const Config& starts, const Config& goals, LacamOptions opt,
                           ActionPreference* pref, GoalTest test, std::shared_ptr<DistCache> cache)
    : dist_(g, std::move(cache)), lacam_(g, dist_, without_refine(opt), pref), current_(starts), g_(g), immobile_(starts.size(), 0)
{
  set_goals(goals, std::move(test));
}

void NaiveRtLacam::set_goals(const Config& goals, GoalTest test)
{
  goals_ = goals;
  test_ = std::move(test);
  fresh_ = false;
  solution_.clear();
}

void NaiveRtLacam::set_immobile(int agent, bool immobile)
{
  check_immobile_agent(agent, immobile_.size());
  immobile_[agent] = immobile;
  lacam_.set_immobile(immobile_);
  fresh_ = false;      // the next search starts from current_ with the mask
  solution_.clear();   // a path found before may move the agent
}

void NaiveRtLacam::set_immobile(const std::vector<uint8_t>& immobile)
{
  check_marks(immobile, immobile_.size());
  for (size_t i = 0; i < immobile.size(); ++i) immobile_[i] = immobile[i] != 0;
  lacam_.set_immobile(immobile_);
  fresh_ = false;
  solution_.clear();
}

bool NaiveRtLacam::restart_at(const Config& at, const Config& goals, GoalTest test, const std::vector<uint8_t>& immobile)
{
  check_restart(at, goals, immobile, current_.size());
  current_ = at;
  set_goals(goals, std::move(test));
  set_immobile(immobile);
  return true;
}

Status NaiveRtLacam::search(const Budget& b)
{
  if (!solution_.empty()) return Status::Solved;
  if (!fresh_) {
    lacam_.reset(current_, goals_, relaxed_goal_test(g_, current_, goals_, immobile_, test_));
    fresh_ = true;
  }
  const Status s = lacam_.search(b);
  if (s == Status::Solved) solution_ = lacam_.path(lacam_.goal_node()), at_ = 0;
  return s;
}

const HNode* NaiveRtLacam::planned() const
{
  if (!fresh_) return nullptr;
  const HNode* target = lacam_.status() == Status::Solved ? lacam_.goal_node() : lacam_.top();
  return lacam_.next_toward(target);
}

const Config& NaiveRtLacam::next()
{
  if (!solution_.empty()) return next_ = solution_[std::min(at_ + 1, solution_.size() - 1)];
  const HNode* h = planned();
  if (h) next_.assign(h->C, h->C + lacam_.num_agents());
  else next_ = current_;
  return next_;
}

void NaiveRtLacam::commit()
{
  next();
  current_ = next_;
  fresh_ = false;
  if (at_ + 1 < solution_.size()) ++at_;  // index, not erase: O(1) per step
}

bool NaiveRtLacam::at_goal() const
{
  return passes_goal_test(test_, current_, goals_);
}

}  // namespace planner
