#pragma once
// PibtPlanner: PIBT alone as a real-time planner (no search): each iteration is one PIBT
// step with dynamic priorities. Incomplete; the paper's PIBT baseline.
#include "planner/lacam/priority.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/realtime_planner.hpp"

namespace planner {

class PibtPlanner : public RealtimePlanner {
 public:
  PibtPlanner(const Graph& g, const Config& starts, const Config& goals, LacamOptions opt = {},
              ActionPreference* pref = nullptr, GoalTest test = {},
              std::shared_ptr<DistCache> cache = nullptr);

  Status search(const Budget& b) override;  // plans the next step once; the budget is not needed
  const Config& next() override { return planned_ ? next_ : current_; }
  void commit() override;
  void set_goals(const Config& goals, GoalTest test = {}) override;
  void set_max_dist_tables(size_t n) override { dist_.set_max_tables(n); }
  void share_dist_cache(std::shared_ptr<DistCache> c) override { dist_.share(std::move(c)); }
  void set_immobile(int agent, bool immobile) override;
  void set_immobile(const std::vector<uint8_t>& immobile) override;  // one update for all
  bool restart_at(const Config& at, const Config& goals, GoalTest test, const std::vector<uint8_t>& immobile) override;
  void set_priority_hint(std::vector<float> hint) override { hint_ = std::move(hint); }
  void set_pockets(std::vector<Vertex> pocket, float cost) override { pibt_.set_pockets(std::move(pocket), cost); }

  const Config& current() const override { return current_; }
  const Config& goals() const override { return goals_; }
  bool at_goal() const override;
  uint64_t expansions() const override { return steps_planned_; }
  size_t explored() const override { return 0; }
  std::string name() const override { return "pibt"; }
  const Graph* graph() const override { return &dist_.graph(); }

 private:
  DistTable dist_;
  Pibt pibt_;
  std::shared_ptr<const Zones> zones_;  // LacamOptions::zones, kept alive for pibt_
  Rng rng_;
  Config current_, goals_, next_;
  GoalTest test_;
  std::vector<float> prio_, prio_next_;
  std::vector<float> hint_;  // the task layer's priority hints, applied at set_goals
  std::vector<int32_t> order_;
  std::vector<uint8_t> immobile_;  // agent -> 1 while immobile (immobile.hpp)
  bool planned_ = false;
  bool keep_priorities_;
  uint64_t steps_planned_ = 0;
};

}  // namespace planner
