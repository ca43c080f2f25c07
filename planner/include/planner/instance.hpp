#pragma once
// Instance: a MAPF problem on a graph: one start and one goal per agent.
#include <string>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace planner {

struct Instance {
  Config starts;
  Config goals;
  std::string source;             // file it came from, for error messages
  std::vector<int> source_lines;  // line of each agent in `source` (may be empty)

  int num_agents() const { return static_cast<int>(starts.size()); }

  // Throws InputError (naming source:line of the offending agent, or "agent i") when a
  // vertex is off the graph, two agents share a start, two share a goal (only when
  // `distinct_goals`, i.e. one-shot MAPF), or a goal cannot be reached from its start.
  void check(const Graph& g, bool distinct_goals = true) const;

  // Sum over agents of the shortest-path length start -> goal (the SOC lower bound).
  long long soc_lower_bound(const Graph& g) const;
};

}  // namespace planner
