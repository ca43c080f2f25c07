#pragma once
// Helpers shared by the planner tests: tiny maps from strings, instances by cell.
#include <functional>
#include <queue>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "planner/graph.hpp"
#include "planner/instance.hpp"
#include "grid.hpp"

namespace test {

// Cells as (x = column, y = row).
inline planner::Config at(const planner::Graph& g, const std::vector<std::pair<int, int>>& cells)
{
  planner::Config c;
  for (auto [x, y] : cells) c.push_back(g.at(x, y));
  return c;
}

struct Case {
  std::string name;
  std::vector<std::string> rows;
  std::vector<std::pair<int, int>> starts, goals;
};

// Small instances that need search: PIBT alone fails or loops on them.
inline std::vector<Case> hard_cases()
{
  return {
      // Two agents pass each other in a corridor using a one-cell siding.
      {"corridor_siding", {".......", "@@@.@@@"}, {{0, 0}, {6, 0}}, {{6, 0}, {0, 0}}},
      // Three agents reverse their order in a corridor with one siding.
      {"corridor_reverse3", {".......", "@@@.@@@"}, {{0, 0}, {1, 0}, {2, 0}}, {{2, 0}, {1, 0}, {0, 0}}},
      // A tree: a plus-shaped junction, four agents exchange opposite arms.
      {"tree_plus",
       {"@@.@@", "@@.@@", ".....", "@@.@@", "@@.@@"},
       {{2, 0}, {2, 4}, {0, 2}, {4, 2}},
       {{2, 4}, {2, 0}, {4, 2}, {0, 2}}},
      // A loop with a tail: the two agents in the dead-end tail swap order via the ring.
      {"loop_with_tail", {"...", ".@.", "...", ".@@", ".@@"}, {{0, 4}, {0, 3}}, {{0, 3}, {0, 4}}},
      // Siding in the middle of a corridor with agents parked on their goals in the way.
      {"parked_in_corridor",
       {"........", "@@@@.@@@"},
       {{0, 0}, {3, 0}, {7, 0}},
       {{7, 0}, {3, 0}, {0, 0}}},
  };
}

// Unsolvable: a path graph on which the agent at one end must get past the others.
inline Case pocket_unsolvable()
{
  return {"pocket", {"@@@@@@", ".....@", "@@@@.@", "@@@@.@"}, {{4, 3}, {4, 2}, {4, 1}}, {{0, 1}, {4, 3}, {4, 2}}};
}

// Whether `goals` is reachable from `starts` by joint moves, by breadth-first search over
// configurations (the exhaustive checks of tiny instances): agent i at v may go to v or to any
// of options(v); no two agents on one vertex, no two exchanging vertices (the validator's
// rules; rotations along cycles and following are allowed), and `keeps(from, to)` (an extra
// rule, e.g. one-at-a-time zones) holds for every step.
inline bool joint_bfs_solvable(const planner::Config& starts, const planner::Config& goals,
                               const std::function<std::vector<planner::Vertex>(planner::Vertex)>& options,
                               const std::function<bool(const planner::Config&, const planner::Config&)>& keeps = {})
{
  const int k = static_cast<int>(starts.size());
  std::set<planner::Config> seen{starts};
  std::queue<planner::Config> q;
  q.push(starts);
  while (!q.empty()) {
    const planner::Config c = q.front();
    q.pop();
    if (c == goals) return true;
    std::vector<std::vector<planner::Vertex>> opts(k);
    for (int i = 0; i < k; ++i) {
      opts[i].push_back(c[i]);
      for (planner::Vertex u : options(c[i])) opts[i].push_back(u);
    }
    std::vector<size_t> idx(k, 0);
    for (;;) {
      planner::Config nx(k);
      for (int i = 0; i < k; ++i) nx[i] = opts[i][idx[i]];
      bool ok = !keeps || keeps(c, nx);
      for (int i = 0; i < k && ok; ++i)
        for (int j = i + 1; j < k && ok; ++j) ok = nx[i] != nx[j] && !(nx[i] == c[j] && nx[j] == c[i]);
      if (ok && seen.insert(nx).second) q.push(nx);
      int i = 0;
      while (i < k && ++idx[i] == opts[i].size()) idx[i++] = 0;
      if (i == k) break;
    }
  }
  return false;
}

}  // namespace test
