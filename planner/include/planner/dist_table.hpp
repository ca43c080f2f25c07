#pragma once
// DistTable: shortest-path distances to each agent's goal, computed lazily by a BFS that
// runs only as far as the queried vertex. Tables are cached per goal *vertex*: agents that
// share a goal share one table, and a lifelong goal change costs at most one new BFS.
//
// Lifelong runs visit thousands of goals, so the cache is capped: once more than
// `max_tables` exist, set_goals() drops the least recently assigned tables that no agent
// is heading to (tables in use are never dropped, so the cap may be exceeded by them).
// A finished BFS also frees its queue.
#include <memory>
#include <unordered_map>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace planner {

class DistTable {
 public:
  static constexpr int32_t kInf = 1 << 29;  // distance of an unreachable vertex

  // max_tables == 0: keep every table (one-shot instances).
  explicit DistTable(const Graph& g, size_t max_tables = 0);
  void set_max_tables(size_t max_tables) { max_tables_ = max_tables; }

  // Makes goals[i] the goal of agent i (cached tables are kept).
  void set_goals(const Config& goals);
  int num_agents() const { return static_cast<int>(agent_table_.size()); }

  // Distance from v to agent i's goal.
  int32_t get(int agent, Vertex v)
  {
    Table& t = *agent_table_[agent];
    int32_t d = t.dist[v];
    return d != kInf ? d : t.extend_until(v, g_);
  }
  // Distance from v to `goal` (creates the table on first use).
  int32_t from_goal(Vertex goal, Vertex v);

  size_t num_tables() const { return tables_.size(); }

 private:
  struct Table {
    std::vector<int32_t> dist;
    std::vector<Vertex> queue;  // BFS order; [head, end) is the open frontier
    size_t head = 0;
    Vertex goal;
    uint64_t last_assigned = 0;  // set_goals() call that last gave it to an agent
    Table(const Graph& g, Vertex goal);
    int32_t extend_until(Vertex v, const Graph& g);
  };
  Table* table_for(Vertex goal);
  void evict();

  const Graph& g_;
  size_t max_tables_;
  uint64_t assign_round_ = 0;
  std::vector<std::unique_ptr<Table>> tables_;
  std::unordered_map<Vertex, Table*> by_goal_;
  std::vector<Table*> agent_table_;
};

}  // namespace planner
