#pragma once
// DistTable: shortest-path distances to each agent's goal, computed lazily by a BFS that
// runs only as far as the queried vertex. The tables live in a DistCache keyed by goal
// *vertex*: agents that share a goal share one table, a lifelong goal change costs at most
// one new BFS, and several DistTables (planner, preference, task assigner) may share one
// cache (share()), so each goal cell is searched once for all of them.
//
// Lifelong runs visit thousands of goals, so the cache is capped: once more than
// `max_tables` exist, the least recently used tables that no agent is heading to are
// dropped (tables in use are never dropped, so the cap may be exceeded by them). See
// dist_cache.hpp for prefetching the tables of goals to come.
#include <memory>
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_cache.hpp"
#include "planner/graph.hpp"

namespace planner {

class DistTable {
 public:
  static constexpr int32_t kInf = DistCache::kInf;  // distance of an unreachable vertex

  // A table set of its own; max_tables == 0: keep every table (one-shot instances).
  explicit DistTable(const Graph& g, size_t max_tables = 0);
  DistTable(const Graph& g, std::shared_ptr<DistCache> cache);  // null: a cache of its own
  ~DistTable();
  DistTable(const DistTable&) = delete;
  DistTable& operator=(const DistTable&) = delete;

  // Switches to `cache` (shared with other holders), keeping the agents' goals.
  void share(std::shared_ptr<DistCache> cache);
  const std::shared_ptr<DistCache>& cache() const { return cache_; }
  void set_max_tables(size_t max_tables) { cache_->set_max_tables(max_tables); }

  // Makes goals[i] the goal of agent i (cached tables are kept).
  void set_goals(const Config& goals);
  int num_agents() const { return static_cast<int>(agent_table_.size()); }

  // Distance from v to agent i's goal.
  int32_t get(int agent, Vertex v) { return agent_table_[agent]->at(v, g_); }
  DistCache::Table* table(int agent) const { return agent_table_[agent]; }  // agent i's goal's table
  // Asks the CPU to start loading agent i's distance of v (no effect on results). A PIBT
  // call reads a few cells around every agent, each agent in its own table: thousands of
  // cache misses, which prefetching them all first overlaps instead of paying one by one.
  void prefetch(int agent, Vertex v) const { __builtin_prefetch(agent_table_[agent]->dist.data() + v); }
  // Distance from v to `goal` (creates the table on first use).
  int32_t from_goal(Vertex goal, Vertex v) { return cache_->table(goal)->at(v, g_); }

  size_t num_tables() const { return cache_->num_tables(); }
  const Graph& graph() const { return g_; }

 private:
  void unpin_all();

  const Graph& g_;
  std::shared_ptr<DistCache> cache_;
  std::vector<DistCache::Table*> agent_table_;  // pinned in cache_
};

}  // namespace planner
