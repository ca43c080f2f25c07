#pragma once
// Helpers shared by the planner tests: tiny maps from strings, instances by cell.
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

}  // namespace test
