// ErrandStalls (tasks/errand_stalls.hpp): open ticks and stall ticks of errands, with
// agents moved by hand so that every number is exact.
#include <gtest/gtest.h>

#include "tasks/errand_stalls.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/task_pool.hpp"
#include "tasks/greedy_assigner.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;
using planner::Config;
using planner::Vertex;

// One agent on a corridor x = 0..9, errand at x = 9, from x = 0: three moves on (marks at
// 1, 2, 3), five steps standing (4..8), two back (9, 10), two forward again to x = 3
// (11, 12: no closer than its best, 6 away), then on to the errand (13..18). The stall is
// the gap from the mark at step 3 to the next at step 13: 10; open: 18 steps.
TEST(ErrandStalls, AStallIsTheLongestStretchWithoutGettingCloserThanBefore)
{
  const planner::Graph g = ttest::grid({".........."});
  ErrandStalls s(g);
  std::vector<int> xs{0, 1, 2, 3, 3, 3, 3, 3, 3, 2, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const std::vector<ErrandStalls::Held> held{{7, 0, g.at(9, 0)}};
  for (long t = 0; t < static_cast<long>(xs.size()); ++t) {
    if (xs[t] == 9) {
      s.completed(t, 7, 0);
    } else {
      s.observe(t, held, Config{g.at(xs[t], 0)});
    }
    if (t == 12) {
      EXPECT_EQ(s.stalled(t, 7), 9);  // since the mark at step 3
    }
  }
  const ErrandStalls::Summary m = s.summary(18);
  EXPECT_EQ(m.errands, 1);
  EXPECT_EQ(m.max_open, 18);
  EXPECT_EQ(m.max_stall, 10);
  EXPECT_EQ(s.stalled(18, 7), 0);  // completed: nothing open
}

// An errand still open at the end counts to the end; an errand handed to another agent keeps
// its clock (the new holder's distance is its new best, not a mark).
TEST(ErrandStalls, OpenErrandsCountToTheEndAndANewHolderIsNoProgress)
{
  const planner::Graph g = ttest::grid({".........."});
  ErrandStalls s(g);
  const Vertex goal = g.at(9, 0);
  s.observe(0, {{3, 0, goal}, {}}, Config{g.at(0, 0), g.at(5, 0)});
  s.observe(1, {{3, 0, goal}, {}}, Config{g.at(1, 0), g.at(5, 0)});  // mark
  s.observe(2, {{}, {3, 0, goal}}, Config{g.at(1, 0), g.at(5, 0)});  // handed to agent 1, nearer: no mark
  s.observe(3, {{}, {3, 0, goal}}, Config{g.at(1, 0), g.at(5, 0)});
  EXPECT_EQ(s.stalled(3, 3), 2);
  s.observe(4, {{}, {3, 0, goal}}, Config{g.at(1, 0), g.at(6, 0)});  // mark
  EXPECT_EQ(s.stalled(4, 3), 0);
  const ErrandStalls::Summary m = s.summary(10);  // open: counted to step 10
  EXPECT_EQ(m.max_open, 10);
  EXPECT_EQ(m.max_stall, 6);
}

// Through the TaskManager: busy agents only. Agent 0 holds the only task and is moved to its
// errand; the other agent (idle) stands still the whole run and adds nothing.
TEST(ErrandStalls, TheTaskManagerCountsBusyAgentsOnly)
{
  const planner::Graph g = ttest::grid({"......", "......"});
  auto file = ttest::task_file(g, {{{5, 0}}});
  TaskPool pool(file, g, 1, std::make_unique<GreedyAssigner>());
  pool.watch_stalls(g);
  Config at{g.at(0, 0), g.at(0, 1)};
  pool.start(at);
  ASSERT_TRUE(pool.busy(0) != pool.busy(1));
  const int a = pool.busy(0) ? 0 : 1;
  for (long t = 1; t <= 20; ++t) {
    if (t > 10 && g.cell_x(at[a]) < 5) at[a] = g.at(g.cell_x(at[a]) + 1, g.cell_y(at[a]));  // waits 10 steps first
    pool.update(t, at);
    if (pool.tasks_finished() > 0) break;
  }
  ASSERT_EQ(pool.errands_finished(), 1);
  const ErrandStalls::Summary m = pool.stall_summary();
  EXPECT_EQ(m.errands, 2);  // and the next task's, given at step 15
  EXPECT_EQ(m.max_open, 15);  // 10 waiting + 5 moves
  EXPECT_EQ(m.max_stall, 11);  // from the start's mark to the first move at step 11
}
