// Task semantics on hand-made instances, driven by hand (no planner): exact completions.
#include <gtest/gtest.h>

#include "tasks/greedy_assigner.hpp"
#include "tasks/hungarian_assigner.hpp"
#include "tasks/lifelong_goal.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/task_layer.hpp"
#include "tasks/task_pool.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;
using planner::Config;

namespace {

// A 6 x 1 corridor: cell x is vertex x.
const planner::Graph& corridor()
{
  static const planner::Graph g = ttest::grid({"......"});
  return g;
}

}  // namespace

TEST(RoundRobin, AgentIGetsTasksIPlusKN)
{
  const auto& g = corridor();
  // Lines 0..4 (one errand each); 2 agents: agent 0 gets 0, 2, 4, 1 (=6 mod 5), ...
  auto file = ttest::task_file(g, {{{1, 0}}, {{4, 0}}, {{2, 0}}, {{5, 0}}, {{3, 0}}});
  RoundRobin rr(file);
  rr.start({0, 5});
  EXPECT_EQ(rr.mode(), "roundrobin");
  EXPECT_EQ(rr.goals(), (Config{1, 4}));

  EXPECT_TRUE(rr.update(1, {0, 5}).empty());       // nobody there
  EXPECT_EQ(rr.update(2, {1, 5}), (std::vector<Event>{{2, 0, 0, 0}}));
  EXPECT_EQ(rr.goals(), (Config{2, 4}));            // agent 0 -> task 2
  EXPECT_EQ(rr.update(3, {2, 4}), (std::vector<Event>{{3, 0, 2, 0}, {3, 1, 1, 0}}));
  EXPECT_EQ(rr.goals(), (Config{3, 5}));            // agent 0 -> task 4, agent 1 -> task 3
  EXPECT_EQ(rr.update(4, {3, 5}), (std::vector<Event>{{4, 0, 4, 0}, {4, 1, 3, 0}}));
  // Cyclic: agent 0's next task is id 6 = line 1, agent 1's id 5 = line 0.
  ASSERT_NE(rr.task_of(0), nullptr);
  EXPECT_EQ(rr.task_of(0)->id, 6);
  EXPECT_EQ(rr.task_of(0)->line, 1);
  EXPECT_EQ(rr.task_of(1)->line, 0);
  EXPECT_EQ(rr.goals(), (Config{4, 1}));
  EXPECT_EQ(rr.errands_finished(), 5);
  EXPECT_EQ(rr.tasks_finished(), 5);
}

TEST(RoundRobin, OneErrandPerAgentPerStep)
{
  const auto& g = corridor();
  // Agent 0's tasks 0 and 2 are both at x=1: standing there completes one per step.
  auto file = ttest::task_file(g, {{{1, 0}}, {{5, 0}}, {{1, 0}}, {{5, 0}}});
  RoundRobin rr(file);
  rr.start({1, 3});
  // Standing on the goal at the start does not count before a step has ended.
  EXPECT_EQ(rr.update(1, {1, 3}), (std::vector<Event>{{1, 0, 0, 0}}));
  EXPECT_EQ(rr.update(2, {1, 3}), (std::vector<Event>{{2, 0, 2, 0}}));
  EXPECT_EQ(rr.update(3, {1, 3}), (std::vector<Event>{{3, 0, 4, 0}}));  // id 4 = line 0, x=1 again
  EXPECT_TRUE(rr.update(4, {0, 3}).empty());
}

TEST(RoundRobin, MultiErrandTasksAndDuplicateGoals)
{
  const auto& g = corridor();
  // Both agents' tasks end at x=3 (a shared station): nothing assumes distinct goals.
  auto file = ttest::task_file(g, {{{1, 0}, {3, 0}}, {{5, 0}, {3, 0}}});
  RoundRobin rr(file);
  rr.start({0, 4});
  EXPECT_EQ(rr.update(1, {1, 5}), (std::vector<Event>{{1, 0, 0, 0}, {1, 1, 1, 0}}));
  EXPECT_EQ(rr.goals(), (Config{3, 3}));
  EXPECT_EQ(rr.tasks_finished(), 0);
  EXPECT_EQ(rr.update(2, {3, 4}), (std::vector<Event>{{2, 0, 0, 1}}));
  EXPECT_EQ(rr.tasks_finished(), 1);
  EXPECT_EQ(rr.errands_finished(), 3);
  EXPECT_EQ(rr.task_of(0)->id, 2);  // line 0 again
}

TEST(TaskPool, RevealAssignComplete)
{
  const auto& g = corridor();
  // Two-errand tasks (pick-up, drop). Pool of 3 for 2 agents.
  auto file = ttest::task_file(g, {
                                      {{5, 0}, {4, 0}},  // 0: far from both
                                      {{1, 0}, {2, 0}},  // 1: near agent 0
                                      {{3, 0}, {0, 0}},  // 2: near agent 1 (chain 3)
                                      {{0, 0}, {1, 0}},  // 3: revealed when one finishes
                                  });
  TaskPool pool(file, g, 3, std::make_unique<GreedyAssigner>());
  pool.start({0, 4});
  EXPECT_EQ(pool.mode(), "pool");
  EXPECT_EQ(pool.revealed(), 3);
  // Greedy, agent 0 first: costs from x=0: task0 5+1, task1 1+1, task2 3+3 -> task 1.
  // Agent 1 from x=4: task0 1+1=2, task2 1+3=4 -> task 0.
  ASSERT_NE(pool.task_of(0), nullptr);
  EXPECT_EQ(pool.task_of(0)->id, 1);
  EXPECT_EQ(pool.task_of(1)->id, 0);
  EXPECT_EQ(pool.goals(), (Config{1, 5}));

  EXPECT_EQ(pool.update(1, {1, 5}), (std::vector<Event>{{1, 0, 1, 0}, {1, 1, 0, 0}}));
  EXPECT_TRUE(pool.task_of(0)->opened());
  EXPECT_EQ(pool.goals(), (Config{2, 4}));
  EXPECT_EQ(pool.revealed(), 3);  // nothing finished yet
  EXPECT_EQ(pool.update(2, {2, 4}), (std::vector<Event>{{2, 0, 1, 1}, {2, 1, 0, 1}}));
  EXPECT_EQ(pool.tasks_finished(), 2);
  EXPECT_EQ(pool.revealed(), 5);  // ids 3, 4 (= line 0 again)
  // Free: task 2 (3->0), task 3 (0->1), task 4 (5->4). Agent 0 at x=2: 1+3, 2+1, 3+1 -> task 3 (id 3, cost 3).
  // Agent 1 at x=4: task 2: 1+3=4, task 4: 1+1=2 -> task 4.
  EXPECT_EQ(pool.task_of(0)->id, 3);
  EXPECT_EQ(pool.task_of(1)->id, 4);
  EXPECT_EQ(pool.goals(), (Config{0, 5}));
}

TEST(TaskPool, HungarianBeatsGreedyOnTheClassicTrap)
{
  const auto& g = corridor();
  // Agent 0 at x=2, agent 1 at x=0; one-errand tasks A at x=1, B at x=5.
  // A at x=1, B at x=5. Greedy: agent 0 takes A (1), agent 1 is left with B (5): 6.
  // Matching: agent 1 -> A (1), agent 0 -> B (3): 4.
  auto file = ttest::task_file(g, {{{1, 0}}, {{5, 0}}});
  TaskPool greedy(file, g, 2, std::make_unique<GreedyAssigner>());
  greedy.start({2, 0});
  EXPECT_EQ(greedy.goals(), (Config{1, 5}));
  TaskPool hung(file, g, 2, std::make_unique<HungarianAssigner>());
  hung.start({2, 0});
  EXPECT_EQ(hung.goals(), (Config{5, 1}));
}

// Agent 1 holds a far task it has not opened when agent 0 finishes next to it and a task
// appears next to agent 1: with `reassign` they swap, without it they must cross.
TEST(TaskPool, ReassignMovesUnopenedTasksToTheNearerAgent)
{
  const auto& g = corridor();
  auto file = ttest::task_file(g, {{{1, 0}}, {{0, 0}}, {{5, 0}}, {{3, 0}, {2, 0}}});
  for (bool reassign : {false, true}) {
    SCOPED_TRACE(reassign ? "reassign" : "keep");
    TaskPool pool(file, g, 2, std::make_unique<GreedyAssigner>(), reassign);
    pool.start({2, 5});
    // Greedy, agent 0 first: from x=2, task 0 (x=1) costs 1, task 1 (x=0) 2 -> task 0; agent 1 -> task 1.
    EXPECT_EQ(pool.goals(), (Config{1, 0}));
    EXPECT_EQ(pool.update(1, {1, 4}), (std::vector<Event>{{1, 0, 0, 0}}));  // task 0 done; task 2 (x=5) revealed
    if (!reassign) {
      EXPECT_EQ(pool.goals(), (Config{5, 0}));  // agent 0 takes the only free task
      EXPECT_EQ(pool.reassignments(), 0);
      continue;
    }
    // Task 1 is unopened and agent 0 (x=1) is nearer to it than agent 1 (x=4): agent 0 takes it
    // (cost 1 vs 4 for task 2); agent 1, now free, takes task 2 in the next round.
    EXPECT_EQ(pool.goals(), (Config{0, 5}));
    EXPECT_EQ(pool.task_of(0)->id, 1);
    EXPECT_EQ(pool.task_of(1)->id, 2);
    EXPECT_EQ(pool.reassignments(), 1);
    // Agent 1 finishes task 2 (one errand; reveals task 3 = line 3 at x=3, x=2) while agent 0
    // still walks to task 1: agent 1 (x=5) is not nearer to task 1 than agent 0 (x=1), so it
    // may not take it and takes task 3.
    EXPECT_EQ(pool.update(2, {1, 5}), (std::vector<Event>{{2, 1, 2, 0}}));
    EXPECT_EQ(pool.task_of(0)->id, 1);
    EXPECT_EQ(pool.task_of(1)->id, 3);
    EXPECT_EQ(pool.reassignments(), 1);
    // Agent 1 opens task 3 at x=3; agent 0 finishes task 1 in the same step and must not take task 3.
    EXPECT_EQ(pool.update(3, {0, 3}), (std::vector<Event>{{3, 0, 1, 0}, {3, 1, 3, 0}}));
    EXPECT_EQ(pool.task_of(1)->id, 3);
    EXPECT_TRUE(pool.task_of(1)->opened());
    EXPECT_EQ(pool.task_of(0)->id, 4);  // line 0 again, revealed when task 1 finished
    EXPECT_EQ(pool.goals(), (Config{1, 2}));
  }
}

TEST(TaskPool, IdleAgentsWaitWhenTasksRunOut)
{
  const auto& g = corridor();
  auto file = ttest::task_file(g, {{{5, 0}}});
  TaskPool pool(file, g, 1, std::make_unique<GreedyAssigner>());
  pool.start({0, 2});
  EXPECT_TRUE(pool.busy(0));      // greedy: agent 0 chooses first
  EXPECT_FALSE(pool.busy(1));
  EXPECT_EQ(pool.goals()[1], 2);  // agent 1 idles in place
  // Its idle goal is its own cell and it is not pending in the goal test.
  const auto test = lifelong_goal_test(pool, {0, 2});
  const planner::Vertex c0[] = {0, 2};
  const planner::Vertex c1[] = {5, 3};
  EXPECT_FALSE(test(c0));
  EXPECT_TRUE(test(c1));
}

TEST(LifelongGoal, SomePendingAgentOnItsGoal)
{
  // Agents 0, 1 pending; agent 2 already on its goal (arrived); agent 3 idle.
  const Config goals{5, 5, 2, 3}, pos{0, 1, 2, 3};
  const auto test = lifelong_goal_test(goals, pos, {1, 1, 1, 0});
  const planner::Vertex root[] = {0, 1, 2, 3};
  const planner::Vertex dup[] = {5, 1, 2, 3};    // a shared goal: one agent there is enough
  const planner::Vertex other[] = {0, 5, 4, 3};
  const planner::Vertex arrived_only[] = {0, 1, 2, 4};
  EXPECT_FALSE(test(root));
  EXPECT_TRUE(test(dup));
  EXPECT_TRUE(test(other));
  EXPECT_FALSE(test(arrived_only));
  // Nobody pending: everything passes (the planner may wait).
  const auto all = lifelong_goal_test(Config{0, 1}, Config{0, 1}, {1, 1});
  EXPECT_TRUE(all(root));
}

// The free-flow bound (free_flow.hpp): each agent alone drives start -> its finished errands'
// cells along shortest paths; the bound is agents / (free-flow steps per errand).
TEST(FreeFlowBound, PricesEachAgentsErrandSequenceAlongShortestPaths)
{
  const auto& g = corridor();
  auto file = ttest::task_file(g, {{{1, 0}}, {{4, 0}}, {{2, 0}}, {{5, 0}}, {{3, 0}}});
  RoundRobin rr(file);
  auto cache = std::make_shared<planner::DistCache>(g);
  rr.set_free_flow(std::make_unique<FreeFlowBound>(cache));
  rr.start({0, 5});                      // goals 1 (agent 0) and 4 (agent 1)
  ASSERT_NE(rr.free_flow(), nullptr);
  EXPECT_EQ(rr.free_flow()->errands_per_step(), 0.0);  // nothing finished yet
  // Agent 0 reaches 1 (1 move from 0) after wandering; the bound does not see the detour.
  rr.update(1, {0, 5});
  rr.update(2, {1, 5});                  // agent 0: 0 -> 1 = 1 step; next goal 2
  rr.update(3, {2, 4});                  // agent 0: 1 -> 2 = 1; agent 1: 5 -> 4 = 1
  EXPECT_EQ(rr.free_flow()->errands(), 3);
  EXPECT_DOUBLE_EQ(rr.free_flow()->steps(), 3.0);
  EXPECT_DOUBLE_EQ(rr.free_flow()->errands_per_step(), 2.0 * 3 / 3.0);
  // Agent 0 -> task 4 (cell 3), agent 1 -> task 3 (cell 5). Their tables' BFS has finished
  // (the planner grew them): a finished table must still answer exactly.
  for (planner::Vertex v : {3, 5})
    for (planner::DistCache::Table* t = cache->table(v); !t->done();) t->pop(g);
  rr.update(4, {3, 5});                  // 2 -> 3 = 1; 4 -> 5 = 1
  EXPECT_DOUBLE_EQ(rr.free_flow()->steps(), 5.0);
  EXPECT_EQ(rr.free_flow()->errands(), 5);
}

TEST(FreeFlowBound, ACostPricesMovesAsTheExecutorDrivesThem)
{
  const auto& g = corridor();
  auto file = ttest::task_file(g, {{{5, 0}}, {{0, 0}}});
  RoundRobin rr(file);
  // E.g. SUMO: a rest-to-rest trapezoid per errand; here 2 steps per move plus 3 per errand.
  rr.set_free_flow(std::make_unique<FreeFlowBound>(std::make_shared<planner::DistCache>(g),
                                                   [](int moves) { return 2.0 * moves + 3.0; }));
  rr.start({0, 5});                      // agent 0 -> 5, agent 1 -> 0
  rr.update(1, {5, 0});                  // both: 5 moves each
  EXPECT_DOUBLE_EQ(rr.free_flow()->steps(), 2 * (2.0 * 5 + 3.0));
  EXPECT_DOUBLE_EQ(rr.free_flow()->errands_per_step(), 2.0 * 2 / 26.0);
}

// Finished errands alone are biased to the short ones (free_flow.hpp): agent 0 finishes two
// 1-move errands while agent 1 is still on its 5-move one. Finished only: 2 agents x 2
// errands / 2 steps = 2.0 errands per step, though the fleet cannot keep up 1.2 (agent 0: 1
// per step, agent 1: 1 per 5). With the open errands priced whole (agent 0: 0 -> 1, 1 move;
// agent 1: 5 -> 0, 5 moves): 2 x 4 / 8 = 1.0.
TEST(FreeFlowBound, OpenErrandsArePricedWholeSoShortFinishesDoNotBiasIt)
{
  const auto& g = corridor();
  // Round robin over 2 agents: agent 0 gets tasks 0, 2, 4; agent 1 gets 1, 3.
  auto file = ttest::task_file(g, {{{1, 0}}, {{0, 0}}, {{0, 0}}, {{5, 0}}, {{1, 0}}});
  RoundRobin rr(file);
  rr.set_free_flow(std::make_unique<FreeFlowBound>(std::make_shared<planner::DistCache>(g)));
  rr.start({0, 5});  // agent 0 -> 1, agent 1 -> 0
  EXPECT_EQ(rr.open_errands(), (planner::Config{1, 0}));
  EXPECT_DOUBLE_EQ(rr.free_flow_bound(), 2.0 * 2 / 6.0);  // nothing finished: the open ones alone
  rr.update(1, {1, 4});  // agent 0: 0 -> 1; next 0
  rr.update(2, {0, 3});  // agent 0: 1 -> 0; next 1
  EXPECT_EQ(rr.free_flow()->errands(), 2);
  EXPECT_DOUBLE_EQ(rr.free_flow()->errands_per_step(), 2.0);  // finished only
  const planner::Config open = rr.open_errands();
  EXPECT_EQ(open, (planner::Config{1, 0}));
  EXPECT_DOUBLE_EQ(rr.free_flow()->open_steps(open), 1.0 + 5.0);
  EXPECT_DOUBLE_EQ(rr.free_flow_bound(), 2.0 * 4 / 8.0);
  // Agent 1 arrives: its 5 moves move from open to finished; agent 1 -> 5 (task 3) is open.
  rr.update(3, {1, 0});  // agent 0: 0 -> 1 (next: task 1, cell 0); agent 1: 5 -> 0
  EXPECT_EQ(rr.free_flow()->errands(), 4);
  EXPECT_DOUBLE_EQ(rr.free_flow()->steps(), 1.0 + 1.0 + 1.0 + 5.0);
  EXPECT_EQ(rr.open_errands()[1], 5);
  EXPECT_DOUBLE_EQ(rr.free_flow_bound(), 2.0 * 6 / (8.0 + rr.free_flow()->open_steps(rr.open_errands())));
  // An agent without a task is open on nothing.
  planner::Config none{-1, -1};
  EXPECT_DOUBLE_EQ(rr.free_flow()->errands_per_step(none), rr.free_flow()->errands_per_step());
}

// make_task_layer: the one factory of the controller's YAML, rtlacam-lifelong and Python.
// Each part of TaskLayerOptions reaches the manager with its option struct whole; bad
// fields are one "key: what" naming the YAML key.
TEST(TaskLayer, EveryPartOfTheOptionsReachesTheManager)
{
  const planner::Graph g = ttest::grid({"......", "......"});
  auto file = ttest::task_file(g, {{{1, 0}, {4, 1}}, {{4, 0}, {1, 1}}, {{5, 0}, {0, 1}}});
  TaskLayerOptions o;
  std::unique_ptr<TaskManager> plain = make_task_layer(file, g, o);
  EXPECT_EQ(plain->mode(), "roundrobin");
  EXPECT_EQ(plain->queues(), nullptr);
  EXPECT_EQ(plain->parking(), nullptr);
  EXPECT_EQ(plain->battery(), nullptr);
  EXPECT_FALSE(plain->urgency().on());

  o.mode = "pool";
  o.pool_size = 2;
  o.queues.capacity = 1;
  o.queues.length = 2;
  o.queues.admission = -1;
  o.queues.fifo = false;
  o.urgency = {true, false};
  o.parking = {true, {g.at(0, 0), g.at(5, 1)}};
  o.battery.on = true;
  o.battery.options.task_check = false;
  o.battery.options.rematch = false;
  o.battery.charger_cells = {g.at(2, 1)};
  o.battery.charge_w = 3600;
  std::unique_ptr<TaskManager> tm = make_task_layer(file, g, o);
  EXPECT_EQ(tm->mode(), "pool");
  ASSERT_NE(tm->queues(), nullptr);
  EXPECT_EQ(tm->queues()->options().capacity, 1);
  EXPECT_EQ(tm->queues()->options().length, 2);
  EXPECT_EQ(tm->queues()->options().admission, -1);
  EXPECT_FALSE(tm->queues()->options().fifo);
  EXPECT_TRUE(tm->urgency().stalls);
  EXPECT_FALSE(tm->urgency().battery);
  ASSERT_NE(tm->parking(), nullptr);
  EXPECT_EQ(tm->parking()->cells(), o.parking.cells);
  ASSERT_NE(tm->battery(), nullptr);
  EXPECT_FALSE(tm->battery()->options().task_check);
  EXPECT_FALSE(tm->battery()->options().rematch);
  ASSERT_EQ(tm->battery()->chargers().size(), 1u);
  EXPECT_EQ(tm->battery()->chargers()[0].cell, g.at(2, 1));
  EXPECT_DOUBLE_EQ(tm->battery()->chargers()[0].wh_per_step, 1.0);  // 3600 W for 1 s

  auto error = [&](TaskLayerOptions bad) {
    try {
      make_task_layer(file, g, bad);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  TaskLayerOptions bad = o;
  bad.queues.admission = 0;
  bad.queues.capacity = 3;
  bad.queues.admission = 2;
  EXPECT_EQ(error(bad), "queues.admission: must be >= capacity (3), 0 or -1, got 2");
  bad = o;
  bad.mode = "fifo";
  EXPECT_EQ(error(bad), "assignment: must be roundrobin or pool, not 'fifo'");
  bad = o;
  bad.pool_size = 0;
  EXPECT_EQ(error(bad), "pool_size: must be >= 1, got 0");
  bad = o;
  bad.battery.options.threshold = 0.95;
  EXPECT_EQ(error(bad).rfind("battery.threshold: must be < target", 0), 0u) << error(bad);
}
