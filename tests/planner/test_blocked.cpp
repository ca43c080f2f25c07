// Blocked vertices (planner/blocked.hpp): the graph without the arcs into blocked vertices
// except evacuation arcs. Checked on a path (which arcs remain), and with RT-LaCAM on a
// 5x5 grid whose middle column is blocked but for one gap: every agent reaches its goal
// and no move of the run enters a blocked vertex, while an agent that starts inside the
// blocked column gets out. On the full graph (the facility off) the same instance moves
// agents through the column.
#include <gtest/gtest.h>

#include "planner/blocked.hpp"
#include "planner/solver.hpp"
#include "planner/validator.hpp"

using namespace planner;

namespace {

Graph path5() { return Graph::from_edges(5, {{0, 1}, {1, 2}, {2, 3}, {3, 4}}); }

// Runs RT-LaCAM on `plan_on` for at most 200 steps with 50 expansions each, validating
// every step on the full graph `g`; counts moves into vertices with blocked[v] != 0.
int run(const Graph& g, const Graph& plan_on, const Config& s, const Config& goals, const std::vector<uint8_t>& blocked,
        bool* reached)
{
  auto p = make_planner(Solver::RtLacam, plan_on, s, goals);
  Validator val(g, s, goals);
  Config cur = s;
  int entries = 0;
  for (int t = 0; t < 200 && !p->at_goal(); ++t) {
    Budget b;
    b.expansions = 50;
    p->search(b);
    const Config next = p->next();
    p->commit();
    EXPECT_TRUE(val.step(next)) << val.error();
    for (size_t i = 0; i < next.size(); ++i) entries += next[i] != cur[i] && blocked[next[i]];
    cur = next;
  }
  *reached = p->at_goal();
  return entries;
}

}  // namespace

TEST(Blocked, PathKeepsOnlyArcsOutOfTheBlockedRegion)
{
  const Graph g = path5();
  const std::vector<uint8_t> blocked = {0, 0, 1, 1, 0};
  const std::vector<int32_t> d = exit_distance(g, blocked);
  EXPECT_EQ(d, (std::vector<int32_t>{0, 0, 1, 1, 0}));
  const Graph b = blocked_graph(g, blocked);
  EXPECT_EQ(b.size(), 5);
  EXPECT_TRUE(b.directed());
  EXPECT_FALSE(b.adjacent(1, 2));  // into the region
  EXPECT_FALSE(b.adjacent(4, 3));
  EXPECT_TRUE(b.adjacent(2, 1));   // out of it
  EXPECT_TRUE(b.adjacent(3, 4));
  EXPECT_FALSE(b.adjacent(2, 3));  // inside, no nearer to an exit
  EXPECT_FALSE(b.adjacent(3, 2));
  EXPECT_TRUE(b.adjacent(0, 1) && b.adjacent(1, 0));
  // A deeper region: 1..3 blocked, only 0 open -> 3 -> 2 -> 1 -> 0 is the way out.
  const Graph c = blocked_graph(g, {0, 1, 1, 1, 1});
  EXPECT_TRUE(c.adjacent(4, 3) && c.adjacent(3, 2) && c.adjacent(2, 1) && c.adjacent(1, 0));
  EXPECT_FALSE(c.adjacent(1, 2) || c.adjacent(2, 3) || c.adjacent(3, 4) || c.adjacent(0, 1));
  // Nothing blocked: the same graph.
  const Graph same = blocked_graph(g, std::vector<uint8_t>(5, 0));
  EXPECT_FALSE(same.directed());
  EXPECT_EQ(same.num_arcs(), g.num_arcs());
}

TEST(Blocked, RtLacamRoutesAroundBlockedCellsAndLeavesThem)
{
  std::vector<bool> free(25, true);
  const Graph g = Graph::from_grid(5, 5, free);
  auto at = [&](int x, int y) { return g.at(x, y); };
  std::vector<uint8_t> blocked(25, 0);
  for (int y = 0; y < 4; ++y) blocked[at(2, y)] = 1;  // column x = 2, gap at y = 4
  const Graph b = blocked_graph(g, blocked);
  EXPECT_TRUE(b.is_grid());
  // Left <-> right swaps through the middle, and agent 2 starts inside the column.
  const Config s = {at(0, 0), at(4, 0), at(2, 1)};
  const Config goals = {at(4, 1), at(0, 1), at(0, 3)};
  bool reached = false;
  EXPECT_EQ(run(g, b, s, goals, blocked, &reached), 0);
  EXPECT_TRUE(reached);
  // The facility off: the shortest paths cross the column.
  EXPECT_GT(run(g, g, s, goals, blocked, &reached), 0);
}
