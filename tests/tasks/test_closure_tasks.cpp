// Tasks and closures (tasks/task_manager.hpp, tasks/reachability.hpp; issue 24: "a closure
// that isolates a goal: reassign"). The closed graph is planner::blocked_graph, as the
// controller builds it (controller/run.cpp, closure_tasks()); positions move by hand. The
// SUMO run: Rules.ALifelongErrandCutOffByAClosureGoesToAnotherAgv (tests/controller).
#include <gtest/gtest.h>

#include "planner/blocked.hpp"
#include "tasks/greedy_assigner.hpp"
#include "tasks/reachability.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/task_pool.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;
using planner::Config;
using planner::Vertex;

namespace {

// A corridor x = 0..6 with cell (3, 0) closed: the two halves are cut apart.
struct Corridor {
  planner::Graph g = ttest::grid({"......."});
  planner::Graph closed;
  Corridor()
  {
    std::vector<uint8_t> b(g.size(), 0);
    b[g.at(3, 0)] = 1;
    closed = planner::blocked_graph(g, b);
  }
};

}  // namespace

TEST(Reachability, FollowsArcsOneWayAndStopsAtClosedCells)
{
  Corridor c;
  Reachability r(c.closed);
  EXPECT_TRUE(r.reaches(c.g.at(0, 0), c.g.at(2, 0)));
  EXPECT_FALSE(r.reaches(c.g.at(2, 0), c.g.at(4, 0)));
  EXPECT_FALSE(r.reaches(c.g.at(2, 0), c.g.at(3, 0)));  // the closed cell itself
  EXPECT_TRUE(r.reaches(c.g.at(3, 0), c.g.at(6, 0)));   // out of it: the evacuation arcs
  EXPECT_TRUE(r.reaches(c.g.at(6, 0), c.g.at(4, 0)));
  // Directed: a one-way pair 0 -> 1 only.
  const planner::Graph d = planner::Graph::from_arcs(2, {{0, 1}});
  Reachability rd(d);
  EXPECT_TRUE(rd.reaches(0, 1));
  EXPECT_FALSE(rd.reaches(1, 0));
}

TEST(ClosureTasks, AnErrandCutOffByAClosureGoesToAnAgentThatCanReachIt)
{
  Corridor c;
  auto file = ttest::task_file(c.g, {{{6, 0}}, {{0, 0}}});
  for (bool reassign : {true, false}) {
    SCOPED_TRACE(reassign ? "closure known to the pool" : "mechanism off");
    TaskPool pool(file, c.g, 1, std::make_unique<GreedyAssigner>());
    const Config at{c.g.at(2, 0), c.g.at(4, 0)};
    pool.start(at);  // one task revealed: (6, 0) to agent 0 (the first free one)
    ASSERT_TRUE(pool.busy(0));
    ASSERT_FALSE(pool.busy(1));
    if (reassign) pool.set_open_graph(&c.closed);
    pool.update(1, at);
    if (!reassign) {  // agent 0 keeps an errand it cannot reach
      EXPECT_TRUE(pool.busy(0));
      EXPECT_EQ(pool.goals()[0], c.g.at(6, 0));
      continue;
    }
    EXPECT_EQ(pool.reassigned_for_closure(), 1);
    EXPECT_TRUE(pool.goals_changed());
    EXPECT_FALSE(pool.busy(0));
    ASSERT_TRUE(pool.busy(1));  // agent 1, on the errand's side, took it
    EXPECT_EQ(pool.goals()[1], c.g.at(6, 0));
    // Agent 1 serves it; the next task, (0, 0), is on agent 0's side: agent 0 takes it.
    pool.update(2, {c.g.at(2, 0), c.g.at(5, 0)});
    pool.update(3, {c.g.at(2, 0), c.g.at(6, 0)});
    EXPECT_EQ(pool.tasks_finished(), 1);
    ASSERT_TRUE(pool.busy(0));
    EXPECT_EQ(pool.goals()[0], c.g.at(0, 0));
    EXPECT_EQ(pool.reassigned_for_closure(), 1);
  }
}

TEST(ClosureTasks, AnErrandNobodyCanReachWaitsInThePoolUntilTheClosureEnds)
{
  Corridor c;
  auto file = ttest::task_file(c.g, {{{6, 0}}});
  TaskPool pool(file, c.g, 1, std::make_unique<GreedyAssigner>());
  const Config at{c.g.at(1, 0)};
  pool.start(at);
  pool.set_open_graph(&c.closed);
  pool.update(1, at);
  EXPECT_FALSE(pool.busy(0));  // handed back; nobody else can take it
  EXPECT_EQ(pool.reassigned_for_closure(), 1);
  for (long t = 2; t < 5; ++t) {
    pool.update(t, at);
    EXPECT_FALSE(pool.busy(0)) << "tick " << t;  // never given back while closed
  }
  pool.set_open_graph(nullptr);  // the closure ends
  pool.update(5, at);
  ASSERT_TRUE(pool.busy(0));
  EXPECT_EQ(pool.goals()[0], c.g.at(6, 0));
  EXPECT_EQ(pool.reassigned_for_closure(), 1);
}

TEST(ClosureTasks, ARoundRobinAgentKeepsItsOwnTaskAndWaits)
{
  Corridor c;
  auto file = ttest::task_file(c.g, {{{6, 0}}});
  RoundRobin rr(file);
  const Config at{c.g.at(1, 0)};
  rr.start(at);
  rr.set_open_graph(&c.closed);
  rr.update(1, at);
  EXPECT_TRUE(rr.busy(0));
  EXPECT_EQ(rr.reassigned_for_closure(), 0);
}

TEST(ClosureTasks, TasksNobodyCanReachDoNotFillThePool)
{
  // Pool of one: the revealed task is cut off; the pool reveals the next one, which the agent
  // can reach, and after the closure it is back to one live task at a time.
  Corridor c;
  auto file = ttest::task_file(c.g, {{{6, 0}}, {{0, 0}}, {{2, 0}}});
  TaskPool pool(file, c.g, 1, std::make_unique<GreedyAssigner>());
  Config at{c.g.at(1, 0)};
  pool.start(at);
  pool.set_open_graph(&c.closed);
  pool.update(1, at);
  ASSERT_TRUE(pool.busy(0));  // not idle behind the cut-off task
  EXPECT_EQ(pool.goals()[0], c.g.at(0, 0));
  EXPECT_EQ(pool.revealed(), 2);
  at[0] = c.g.at(0, 0);
  pool.update(2, at);  // done: the cut-off task is still live, so finishing reveals none
  EXPECT_EQ(pool.tasks_finished(), 1);
  EXPECT_EQ(pool.revealed(), 3);  // top_up: (6, 0) is still unreachable, so (2, 0) comes
  ASSERT_TRUE(pool.busy(0));
  EXPECT_EQ(pool.goals()[0], c.g.at(2, 0));
  pool.set_open_graph(nullptr);  // reopened: (2, 0) done, then (6, 0), nothing new beyond one live
  at[0] = c.g.at(2, 0);
  pool.update(3, at);
  ASSERT_TRUE(pool.busy(0));
  EXPECT_EQ(pool.goals()[0], c.g.at(6, 0));
  EXPECT_EQ(pool.revealed(), 3);
}
