#include "policy/actions.hpp"

namespace policy {

const char* action_name(int a)
{
  static const char* names[kNumActions] = {"stay", "up", "down", "left", "right"};
  return a >= 0 && a < kNumActions ? names[a] : "invalid";
}

int action_of(const planner::Graph& g, planner::Vertex from, planner::Vertex to)
{
  if (from == to) return kStay;
  const int dx = g.cell_x(to) - g.cell_x(from), dy = g.cell_y(to) - g.cell_y(from);
  for (int a = 1; a < kNumActions; ++a)
    if (dx == kActionDx[a] && dy == kActionDy[a]) return a;
  return -1;
}

}  // namespace policy
