#include "planner/lacam/pibt_planner.hpp"

#include <stdexcept>
#include <string>

#include "planner/lacam/immobile.hpp"

namespace planner {

PibtPlanner::PibtPlanner(const Graph& g, const Config& starts, const Config& goals, LacamOptions opt,
                         ActionPreference* pref, GoalTest test, std::shared_ptr<DistCache> cache)
    : dist_(g, std::move(cache)), pibt_(g, dist_, opt.swap), rng_(opt.seed), current_(starts), keep_priorities_(opt.keep_priorities)
{
  pibt_.set_preference(pref);
  pibt_.set_free_first(opt.free_first);
  zones_ = opt.zones;
  pibt_.set_zones(zones_.get());
  set_goals(goals, std::move(test));
}

void PibtPlanner::set_goals(const Config& goals, GoalTest test)
{
  goals_ = goals;
  test_ = std::move(test);
  dist_.set_goals(goals);
  pibt_.set_goals(goals);
  const int n = static_cast<int>(goals.size());
  next_.assign(n, -1);
  planned_ = false;
  // Lifelong goal changes may keep the priorities: PIBT's memory of who waited longest.
  const bool keep = keep_priorities_ && static_cast<int>(prio_.size()) == n;
  if (keep && static_cast<int>(hint_.size()) != n) return;
  std::vector<float> tie(n);
  init_priorities(current_.data(), n, dist_, tie.data());
  if (!keep) {
    prio_ = tie;
    prio_next_.assign(n, 0.0f);
  }
  raise_to_hint(tie.data(), hint_, n, prio_.data());  // the task layer's hints (priority.hpp)
  order_.resize(n);
  initial_order(prio_.data(), n, order_.data());
}

void PibtPlanner::set_immobile(int agent, bool immobile)
{
  check_immobile_agent(agent, current_.size());
  if (immobile_.size() != current_.size()) immobile_.assign(current_.size(), 0);
  immobile_[agent] = immobile;
  pibt_.set_immobile(immobile_);
  planned_ = false;  // a step planned before may move the agent
}

void PibtPlanner::set_immobile(const std::vector<uint8_t>& immobile)
{
  check_marks(immobile, current_.size());
  immobile_.assign(immobile.size(), 0);
  for (size_t i = 0; i < immobile.size(); ++i) immobile_[i] = immobile[i] != 0;
  pibt_.set_immobile(immobile_);
  planned_ = false;
}

bool PibtPlanner::restart_at(const Config& at, const Config& goals, GoalTest test, const std::vector<uint8_t>& immobile)
{
  check_restart(at, goals, immobile, current_.size());
  current_ = at;
  set_goals(goals, std::move(test));
  set_immobile(immobile);
  return true;
}

Status PibtPlanner::search(const Budget&)
{
  if (!planned_) {
    // A failed PIBT call (possible only with conflicting preferences) leaves everyone in place.
    if (!pibt_.generate(current_.data(), order_.data(), nullptr, next_.data(), rng_)) next_ = current_;
    planned_ = true;
    ++steps_planned_;
  }
  return at_goal() ? Status::Solved : Status::Searching;
}

void PibtPlanner::commit()
{
  if (!planned_) search(Budget{});
  current_ = next_;
  const int n = static_cast<int>(current_.size());
  next_priorities(current_.data(), n, dist_, prio_.data(), prio_next_.data());
  prio_.swap(prio_next_);
  sort_by_priority(prio_.data(), n, order_.data());
  planned_ = false;
}

bool PibtPlanner::at_goal() const
{
  return passes_goal_test(test_, current_, goals_);
}

}  // namespace planner
