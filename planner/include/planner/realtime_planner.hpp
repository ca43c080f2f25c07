#pragma once
// RealtimePlanner: the interface the executors (bench, SUMO controller, lifelong runs) use
// to interleave planning and execution:
//
//   loop:  search(budget)        -- think; may be called several times per move
//          next()                -- the configuration to move to now
//          ...agents execute...
//          commit()              -- they are there: advance
//
// Implementations: RtLacam (persistent, rerooted search: complete), NaiveRtLacam (fresh
// search each iteration), PibtPlanner (one PIBT step per iteration, no search).
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "planner/budget.hpp"
#include "planner/config.hpp"
#include "planner/search_types.hpp"

namespace planner {

class DistCache;
class Graph;
class RotationPlanner;

// The goal test as every planner applies it to its current configuration.
inline bool passes_goal_test(const GoalTest& test, const Config& current, const Config& goals)
{
  return test ? test(current.data()) : current == goals;
}

class RealtimePlanner {
 public:
  virtual ~RealtimePlanner() = default;

  virtual Status search(const Budget& b) = 0;
  virtual const Config& next() = 0;
  virtual void commit() = 0;
  // New goals: a new search rooted at the current configuration (lifelong tasks).
  virtual void set_goals(const Config& goals, GoalTest test = {}) = 0;
  // Immobile agents (a stuck AGV; immobile.hpp): while marked, an agent is never moved in
  // any configuration next() returns, and nobody is planned through it. Setting or clearing
  // the mark restarts the search at current(); while any agent is immobile the search aims
  // at relaxed_goal_test() (the others reach their goals around it), at_goal() keeps the
  // real test. Clearing every mark restores the planner's completeness from current().
  virtual void set_immobile(int agent, bool immobile)
  {
    (void)agent, (void)immobile;
    throw std::logic_error("planner " + name() + " has no immobile agents");
  }
  // Every agent's mark at once (immobile[i] != 0: agent i immobile): one restart for all the
  // changes, where a set_immobile(agent, ..) per agent restarts the search (a reset of the
  // tree and the relaxed goal test, ~0.3 ms at 1000 agents) once per changed agent -- the
  // stuck-AGV replan marks all its stuck AGVs in one SUMO step. Throws
  // std::invalid_argument unless immobile.size() is the number of agents. The default
  // applies the marks one by one.
  virtual void set_immobile(const std::vector<uint8_t>& immobile)
  {
    check_marks(immobile, current().size());
    for (size_t i = 0; i < immobile.size(); ++i) set_immobile(static_cast<int>(i), immobile[i] != 0);
  }
  // A new search at `at`, which the agents reached by moves this planner did not plan (the
  // stuck-AGV replan's cut plan), with new goals, goal test and immobile marks (as above),
  // in one restart: a fresh planner there costs several restarts' time (its arrays, tables'
  // pins, priorities: 1-1.7 ms at 1000 agents, measured in the SUMO replan step). Complete
  // from `at` as a fresh one; it keeps what it learnt (step costs, the random stream, with
  // LacamOptions::keep_priorities the priorities), so its decisions may differ from a fresh
  // one's. false: not supported (the caller builds a fresh planner), nothing changed.
  virtual bool restart_at(const Config& at, const Config& goals, GoalTest test, const std::vector<uint8_t>& immobile)
  {
    (void)at, (void)goals, (void)test, (void)immobile;
    return false;
  }
  // Priority hints (tasks/urgency.hpp): per agent, extra PIBT priority from the task layer (an
  // errand that stalled, a low battery), larger = moves first. Takes effect at the next
  // epoch start (set_goals, restart_at), never inside one: RT-LaCAM's tree of the epoch
  // stays one complete search. Empty: none. Planners without priorities ignore it.
  virtual void set_priority_hint(std::vector<float> hint) { (void)hint; }
  // Foreign-pocket cost (Pibt::set_pockets): PIBT ranks a move into a dead-end pocket other
  // than the agent's goal's `cost` moves worse. Like hints, it only orders PIBT's candidates.
  // Planners without PIBT ignore it.
  virtual void set_pockets(std::vector<Vertex> pocket, float cost) { (void)pocket, (void)cost; }
  // Lifelong runs: cap the distance tables kept for goals no agent has now (0 = no cap).
  virtual void set_max_dist_tables(size_t n) { (void)n; }
  // Lifelong runs: keep the distance tables in `cache`, shared with the task layer and
  // prefetched ahead of goal changes (dist_cache.hpp). Planners without tables ignore it.
  virtual void share_dist_cache(std::shared_ptr<DistCache> cache) { (void)cache; }

  virtual const Config& current() const = 0;
  virtual const Config& goals() const = 0;
  virtual bool at_goal() const = 0;           // current configuration passes the goal test
  virtual bool exhausted() const { return false; }  // proven: no solution
  virtual uint64_t expansions() const = 0;    // total over all iterations
  virtual size_t explored() const = 0;        // size of the current explored table
  virtual std::string name() const = 0;
  // The graph it plans on; nullptr where not known (a test's scripted planner). Callers that
  // take goals from outside check them against it (python/src/module.cpp set_goals).
  virtual const Graph* graph() const { return nullptr; }
  // The costliest expansion of the last search() call in ms (thread CPU), where the planner
  // measures it (RtLacam); -1: not measured (callers then use the mean).
  virtual double max_expansion_ms() const { return -1; }
  // The rotation solvers' own interface (actions, headings, (cell, heading) tables); nullptr
  // for the cell solvers.
  virtual RotationPlanner* rotation() { return nullptr; }

  // search + next: the paper's planning iteration.
  const Config& step(const Budget& b)
  {
    search(b);
    return next();
  }

 protected:
  // The size checks of the batch calls above, one message each for every planner.
  static void check_marks(const std::vector<uint8_t>& immobile, size_t agents)
  {
    if (immobile.size() != agents)
      throw std::invalid_argument("set_immobile: " + std::to_string(immobile.size()) + " marks for " +
                                  std::to_string(agents) + " agents");
  }
  static void check_restart(const Config& at, const Config& goals, const std::vector<uint8_t>& immobile, size_t agents)
  {
    if (at.size() != goals.size() || immobile.size() != goals.size() || at.size() != agents)
      throw std::invalid_argument("restart_at: " + std::to_string(at.size()) + " positions, " +
                                  std::to_string(goals.size()) + " goals, " + std::to_string(immobile.size()) +
                                  " marks for " + std::to_string(agents) + " agents");
  }
};

}  // namespace planner
