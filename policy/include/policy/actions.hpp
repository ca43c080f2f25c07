#pragma once
// Actions: the five moves of an agent on a 4-connected grid, in the order of the policy
// network's outputs. x is the column and y the row of the MovingAI map (Graph::cell_x /
// cell_y), so "up" goes towards row 0:
//   0 stay   1 up (y-1)   2 down (y+1)   3 left (x-1)   4 right (x+1)
// The planner only knows vertices; this is where a vertex move becomes an action index.
#include "planner/graph.hpp"

namespace policy {

constexpr int kNumActions = 5;
enum Action : int { kStay = 0, kUp = 1, kDown = 2, kLeft = 3, kRight = 4 };
constexpr int kActionDx[kNumActions] = {0, 0, 0, -1, 1};
constexpr int kActionDy[kNumActions] = {0, -1, 1, 0, 0};
const char* action_name(int a);

// The action taking an agent from `from` to `to` on grid graph `g`; -1 when the two
// vertices are neither equal nor grid neighbours.
int action_of(const planner::Graph& g, planner::Vertex from, planner::Vertex to);

}  // namespace policy
