#pragma once
// NaiveRtLacam: the baseline of the RT-LaCAM paper. Every iteration runs a fresh LaCAM
// search from the current configuration with the same budget and moves by the same rule:
// root's child toward the top of the DFS stack. Nothing is remembered between iterations,
// so it can cycle forever (livelock). Like RT-LaCAM, once an iteration's search reaches
// the goal the agents follow that path to the end without replanning: a fresh search from
// each point of a found path restarts PIBT's priorities and can walk back, which would
// make the baseline fail even with budgets that solve the whole instance.
#include "planner/lacam/lacam.hpp"
#include "planner/realtime_planner.hpp"

namespace planner {

class NaiveRtLacam : public RealtimePlanner {
 public:
  NaiveRtLacam(const Graph& g, const Config& starts, const Config& goals, LacamOptions opt = {},
               ActionPreference* pref = nullptr, GoalTest test = {},
               std::shared_ptr<DistCache> cache = nullptr);

  Status search(const Budget& b) override;
  const Config& next() override;
  void commit() override;
  void set_goals(const Config& goals, GoalTest test = {}) override;
  void set_max_dist_tables(size_t n) override { dist_.set_max_tables(n); }
  void share_dist_cache(std::shared_ptr<DistCache> c) override { dist_.share(std::move(c)); }
  void set_immobile(int agent, bool immobile) override;
  void set_immobile(const std::vector<uint8_t>& immobile) override;  // one restart for all
  bool restart_at(const Config& at, const Config& goals, GoalTest test, const std::vector<uint8_t>& immobile) override;

  const Config& current() const override { return current_; }
  const Config& goals() const override { return goals_; }
  bool at_goal() const override;
  uint64_t expansions() const override { return lacam_.expansions(); }
  size_t explored() const override { return lacam_.explored(); }
  std::string name() const override { return "naive"; }
  const Graph* graph() const override { return &g_; }

 private:
  const HNode* planned() const;
  void restart();

  DistTable dist_;   // shared by all iterations: BFS once per goal, not per iteration
  Lacam lacam_;
  Config current_, goals_, next_;
  GoalTest test_;
  bool fresh_ = false;  // lacam_ is rooted at current_ and may be continued
  const Graph& g_;
  std::vector<uint8_t> immobile_;  // agent -> 1 while immobile (immobile.hpp)
  std::vector<Config> solution_;  // a found path, once some search solved
  size_t at_ = 0;                 // solution_[at_] is the current configuration
};

}  // namespace planner
