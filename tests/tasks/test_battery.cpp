// Battery (tasks/battery.hpp): drain per metre and per turn, and the charging errand as the
// task layer runs it (TaskManager: a low agent between tasks goes to the nearest free
// charger, takes no task while it charges, and gets its next one at the target). Positions
// are moved by hand, so every charge is exact. The SUMO runs: tests/controller/test_charging.cpp.
#include <gtest/gtest.h>

#include "tasks/battery.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/task_pool.hpp"
#include "tasks/greedy_assigner.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;
using planner::Config;
using planner::Vertex;

namespace {

std::vector<std::pair<double, double>> centres(const planner::Graph& g)
{
  std::vector<std::pair<double, double>> xy;
  for (Vertex v = 0; v < g.size(); ++v) xy.emplace_back(g.cell_x(v), g.cell_y(v));
  return xy;
}

}  // namespace

TEST(Battery, DrainsPerMetreAndPerTurn)
{
  const planner::Graph g = ttest::grid({"...", "...", "..."});
  BatteryOptions o;
  o.capacity_wh = 100;
  o.per_m_wh = 1;
  o.per_turn_wh = 0.5;
  Battery b(g, o, {}, centres(g));
  // Right, right (straight on), down (a turn), left (a turn), right (a reversal: a turn).
  const std::vector<std::pair<int, int>> path{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {2, 1}};
  double expected = 100;
  const std::vector<double> cost{0, 1, 1, 1.5, 1.5, 1.5};
  for (size_t k = 0; k < path.size(); ++k) {
    b.step({g.at(path[k].first, path[k].second)});
    expected -= cost[k];
    EXPECT_DOUBLE_EQ(b.charge(0), expected) << "after step " << k;
  }
  b.step({g.at(2, 1)});  // standing costs nothing
  EXPECT_DOUBLE_EQ(b.charge(0), expected);
  EXPECT_EQ(b.ran_empty(), 0);
}

TEST(Battery, ALowAgentChargesBetweenTasksAndGetsItsNextTaskAtTheTarget)
{
  // A corridor y = 0 with a dead-end charger below its left end.
  const planner::Graph g = ttest::grid({".....", ".####"});
  auto file = ttest::task_file(g, {{{4, 0}, {0, 0}}});
  for (bool charging : {true, false}) {
    RoundRobin rr(file);
    BatteryOptions o;
    o.capacity_wh = 10;
    o.per_m_wh = 1;
    o.threshold = 0.3;
    o.target = 0.8;
    o.charging = charging;
    o.reserve_margin = 0;  // the threshold alone
    rr.set_battery(g, o, {{g.at(0, 1), 2.0, "c"}}, centres(g));
    rr.start({g.at(0, 0)});
    long t = 0;
    auto go = [&](int x, int y) { rr.update(++t, {g.at(x, y)}); };
    for (int x = 1; x <= 4; ++x) go(x, 0);  // errand 1 at (4, 0): 6 Wh left
    for (int x = 3; x >= 0; --x) go(x, 0);  // errand 2 at (0, 0): 2 Wh left, below 3
    EXPECT_EQ(rr.tasks_finished(), 1);
    EXPECT_DOUBLE_EQ(rr.battery()->charge(0), 2.0);
    if (!charging) {  // drain only: straight on to the next task
      EXPECT_TRUE(rr.busy(0));
      EXPECT_EQ(rr.goals()[0], g.at(4, 0));
      EXPECT_EQ(rr.battery()->errands(), 0);
      continue;
    }
    // The charging errand: no task meanwhile, the charger is its goal and it is awaited.
    EXPECT_FALSE(rr.busy(0));
    EXPECT_TRUE(rr.charging(0));
    EXPECT_TRUE(rr.awaited(0));
    EXPECT_EQ(rr.goals()[0], g.at(0, 1));
    EXPECT_EQ(rr.battery()->errands(), 1);
    go(0, 1);  // 1 Wh; then 2 Wh a step on the charger: 3, 5, 7, 9 >= 8
    for (double q : {3.0, 5.0, 7.0}) {
      go(0, 1);
      EXPECT_DOUBLE_EQ(rr.battery()->charge(0), q);
      EXPECT_TRUE(rr.charging(0));
      EXPECT_FALSE(rr.busy(0));
    }
    go(0, 1);
    EXPECT_DOUBLE_EQ(rr.battery()->charge(0), 9.0);
    EXPECT_FALSE(rr.charging(0));
    EXPECT_TRUE(rr.busy(0));  // its next task, handed out as it left the charger
    EXPECT_EQ(rr.goals()[0], g.at(4, 0));
    EXPECT_EQ(rr.battery()->charging_ticks(), 4);
    EXPECT_EQ(rr.battery()->ran_empty(), 0);
  }
}

TEST(Battery, APoolGivesNoTaskToALowAgentAndIdleAgentsKeepOffTheCharger)
{
  const planner::Graph g = ttest::grid({".....", ".####"});
  auto file = ttest::task_file(g, {{{4, 0}}});
  TaskPool pool(file, g, 1, std::make_unique<GreedyAssigner>());
  BatteryOptions o;
  o.capacity_wh = 10;
  o.initial = 0.2;  // below the threshold from the start
  o.per_m_wh = 1;
  pool.set_battery(g, o, {{g.at(0, 1), 5.0, "c"}}, centres(g));
  // Agent 0 starts on the charger, agent 1 beside it.
  pool.start({g.at(0, 1), g.at(1, 0)});
  pool.update(1, {g.at(0, 1), g.at(1, 0)});
  // Both are low: the charger goes to the nearer one (agent 0, on it), the other waits
  // without a task; the pool's task stays unassigned.
  EXPECT_TRUE(pool.charging(0));
  EXPECT_FALSE(pool.charging(1));
  EXPECT_FALSE(pool.busy(0));
  EXPECT_FALSE(pool.busy(1));
  pool.update(2, {g.at(0, 1), g.at(1, 0)});  // 2 + 5 = 7 Wh: not yet at 8
  pool.update(3, {g.at(0, 1), g.at(1, 0)});  // 10 Wh: done, free for the task
  EXPECT_FALSE(pool.charging(0));
  EXPECT_TRUE(pool.charging(1));  // the charger came free: agent 1's turn
  EXPECT_TRUE(pool.busy(0));
  EXPECT_EQ(pool.goals()[1], g.at(0, 1));
}

namespace {

// One step of agent `a` along a shortest path to its goal (no other traffic).
Vertex step_to_goal(const planner::Graph& g, Vertex from, Vertex goal)
{
  if (from == goal) return from;
  std::vector<int> d(g.size(), -1);
  std::vector<Vertex> open{goal};
  d[goal] = 0;
  for (size_t i = 0; i < open.size(); ++i)
    for (Vertex u : g.in_neighbors(open[i]))
      if (d[u] < 0) d[u] = d[open[i]] + 1, open.push_back(u);
  for (Vertex v : g.neighbors(from))
    if (d[v] >= 0 && d[v] < d[from]) return v;
  return from;
}

}  // namespace

// A task longer than the charge: a corridor x = 0..15 with a dead-end charger below its
// right end, one task (15, 0) -> (0, 0) (30 m at 0.5 Wh/m = 15 Wh) for an agent starting at
// (0, 0) with 10 Wh. Below the critical charge (5 Wh) mid-task it hands the task back and
// charges; then it (the only agent) finishes the task. With critical 0 it runs empty.
TEST(Battery, AnAgentBelowTheCriticalChargeMidTaskHandsItsTaskBackAndCharges)
{
  const planner::Graph g = ttest::grid({"................", "###############."});
  auto file = ttest::task_file(g, {{{15, 0}, {0, 0}}});
  for (const std::string mode : {"pool", "roundrobin"})
    for (double critical : {0.25, 0.0}) {
      SCOPED_TRACE(mode + " critical " + std::to_string(critical));
      std::unique_ptr<TaskManager> tm;
      if (mode == "pool") tm = std::make_unique<TaskPool>(file, g, 1, std::make_unique<GreedyAssigner>());
      else tm = std::make_unique<RoundRobin>(file);
      BatteryOptions o;
      o.capacity_wh = 20;
      o.initial = 0.5;
      o.per_m_wh = 0.5;
      o.threshold = 0.3;
      o.critical = critical;
      o.target = 0.9;
      o.reserve_margin = 0;  // the fixed level alone (the reserve: the next test)
      tm->set_battery(g, o, {{g.at(15, 1), 4.0, "c"}}, centres(g));
      Config at{g.at(0, 0)};
      tm->start(at);
      ASSERT_TRUE(tm->busy(0));
      long dropped_at = -1, charging_ticks = 0;
      for (long t = 1; t <= 80 && tm->tasks_finished() == 0; ++t) {
        at[0] = step_to_goal(g, at[0], tm->goals()[0]);
        tm->update(t, at);
        if (tm->dropped_for_charge() > 0 && dropped_at < 0) dropped_at = t;
        charging_ticks += tm->charging(0);
        if (tm->charging(0)) {
          EXPECT_FALSE(tm->busy(0));
          EXPECT_EQ(tm->goals()[0], g.at(15, 1));
        }
      }
      if (critical > 0) {
        // 11 m driven: 4.5 Wh < 5 Wh at (11, 0); 5 m more to the charger.
        EXPECT_EQ(dropped_at, 11);
        EXPECT_EQ(tm->dropped_for_charge(), 1);
        EXPECT_EQ(tm->battery()->errands(), 1);
        EXPECT_GT(charging_ticks, 0);
        EXPECT_EQ(tm->battery()->ran_empty(), 0);
        EXPECT_EQ(tm->tasks_finished(), 1);  // resumed after charging, finished
        EXPECT_EQ(tm->errands_finished(), 2);
      } else {
        EXPECT_EQ(tm->dropped_for_charge(), 0);
        EXPECT_EQ(tm->battery()->ran_empty(), 1);  // 20 m of its 30 m
      }
    }
}

// The distance-aware reserve: the charger is at the far end of the way back. A corridor
// x = 0..15 with a dead-end charger below its left end; one task (15, 0) -> (0, 0) for an
// agent at (0, 0) with 10 of 20 Wh at 0.5 Wh/m; critical 0.1 (2 Wh, 4 m). The fixed level
// trips only on the way back at x = 13 (1.5 Wh), 14 m from the charger: it runs empty. With
// the reserve (margin 1.5) it trips on the way out where the charge no longer covers 1.5 x
// the way back: at x = 8, 6 Wh < 1.5 x 0.5 x 9 m = 6.75 Wh; it turns back and arrives with 1.5 Wh.
TEST(Battery, TheReserveSendsAnAgentToChargeWhileTheWayBackIsStillCovered)
{
  const planner::Graph g = ttest::grid({"................", ".###############"});
  auto file = ttest::task_file(g, {{{15, 0}, {0, 0}}});
  for (double margin : {1.5, 0.0}) {
    SCOPED_TRACE("reserve_margin " + std::to_string(margin));
    auto tm = std::make_unique<TaskPool>(file, g, 1, std::make_unique<GreedyAssigner>());
    BatteryOptions o;
    o.capacity_wh = 20;
    o.initial = 0.5;
    o.per_m_wh = 0.5;
    o.threshold = 0.3;
    o.critical = 0.1;
    o.target = 0.9;
    o.reserve_margin = margin;
    o.task_check = false;  // the mid-task reserve alone (the task check: below)
    tm->set_battery(g, o, {{g.at(0, 1), 4.0, "c"}}, centres(g));
    if (margin > 0) {  // the way: metres and turns (one turn at (0, 0), plus the first move's)
      EXPECT_DOUBLE_EQ(tm->battery()->way_wh(0, g.at(8, 0)), 0.5 * 9);
      EXPECT_DOUBLE_EQ(tm->battery()->way_wh(0, g.at(0, 1)), 0.0);
    }
    Config at{g.at(0, 0)};
    tm->start(at);
    ASSERT_TRUE(tm->busy(0));
    long dropped_at = -1;
    for (long t = 1; t <= 60; ++t) {
      at[0] = step_to_goal(g, at[0], tm->goals()[0]);
      tm->update(t, at);
      if (tm->dropped_for_charge() > 0 && dropped_at < 0) dropped_at = t;
    }
    if (margin > 0) {
      EXPECT_EQ(dropped_at, 8);
      EXPECT_EQ(tm->battery()->ran_empty(), 0);
      EXPECT_GT(tm->battery()->min_charge(), 0.05);
    } else {
      EXPECT_EQ(dropped_at, 17);  // out to x = 15, back to x = 13 on the fixed level
      EXPECT_EQ(tm->battery()->ran_empty(), 1);
    }
  }
}

// Rematched claims: a corridor x = 0..4 with a dead-end charger below each end. Agent 0 in
// the middle claims one charger; agent 1, beside it on that charger's side, gets the other
// (the only one free): each charger lies behind the other agent, head-on. At the next step
// the two swap claims (ways 3 + 2 m against 3 + 4 m): each heads for the charger on its
// own side. With rematch off the claims stay crossed.
TEST(Battery, AgentsOnTheirWayToChargersSwapClaimsThatCross)
{
  const planner::Graph g = ttest::grid({".....", ".###."});
  for (bool rematch : {true, false}) {
    SCOPED_TRACE(rematch ? "rematch" : "no rematch");
    BatteryOptions o;
    o.initial = 0.2;  // below the threshold: both go to charge
    o.per_m_wh = 1;
    o.rematch = rematch;
    Battery b(g, o, {{g.at(0, 1), 1.0, "left"}, {g.at(4, 1), 1.0, "right"}}, centres(g));
    const Vertex mid = g.at(2, 0);
    b.step({mid, mid});  // the start (agent 1's cell is set below)
    ASSERT_TRUE(b.consider(0, mid));
    const bool left = b.goal(0) == g.at(0, 1);
    const Vertex beside = g.at(left ? 1 : 3, 0);
    Config at{mid, beside};
    ASSERT_TRUE(b.consider(1, beside));
    EXPECT_EQ(b.goal(1), g.at(left ? 4 : 0, 1));  // crossed
    b.step(at);  // agent 1 "jumps" beside: 1 m drained, then the rematch
    if (rematch) {
      EXPECT_EQ(b.swaps(), 1);
      EXPECT_EQ(b.goal(0), g.at(left ? 4 : 0, 1));
      EXPECT_EQ(b.goal(1), g.at(left ? 0 : 4, 1));
    } else {
      EXPECT_EQ(b.swaps(), 0);
      EXPECT_EQ(b.goal(1), g.at(left ? 4 : 0, 1));
    }
    b.step(at);  // no further swap: the sum is already the shorter one
    EXPECT_EQ(b.swaps(), rematch ? 1 : 0);
  }
}

// A swap only where both can drive it: a corridor x = 0..6 with a dead-end charger below
// each end, 5 Wh each. Agent 0 at x = 2 claims the left charger (3 m); agent 1 at x = 1 gets
// the right one (6 m): crossed. The swap would shorten the sum (5 + 2 m against 3 + 6 m),
// but at 1.2 Wh/m agent 0's new way (6 Wh) is beyond its 5 Wh: no swap. At 1 Wh/m (5 Wh)
// it is within: the swap is made.
TEST(Battery, ClaimsSwapOnlyWhenEachAgentsChargeCoversItsNewWay)
{
  const planner::Graph g = ttest::grid({".......", ".#####."});
  for (double per_m : {1.2, 1.0}) {
    SCOPED_TRACE("per_m_wh " + std::to_string(per_m));
    BatteryOptions o;
    o.capacity_wh = 10;
    o.initial = 0.5;
    o.threshold = 0.6;  // both low from the start
    o.per_m_wh = per_m;
    Battery b(g, o, {{g.at(0, 1), 1.0, "left"}, {g.at(6, 1), 1.0, "right"}}, centres(g));
    const Config at{g.at(2, 0), g.at(1, 0)};
    b.step(at);
    ASSERT_TRUE(b.consider(0, at[0]));
    ASSERT_TRUE(b.consider(1, at[1]));
    ASSERT_EQ(b.goal(0), g.at(0, 1));
    ASSERT_EQ(b.goal(1), g.at(6, 1));
    b.step(at);  // nobody moved: the rematch alone
    EXPECT_EQ(b.swaps(), per_m > 1.1 ? 0 : 1);
    EXPECT_EQ(b.goal(0), g.at(per_m > 1.1 ? 0 : 6, 1));
  }
}

// The task check: a corridor x = 0..15 with a dead-end charger below its left end, one task
// (15, 0) -> (14, 0) (16 moves at 0.5 Wh/m: 8 Wh; then 7.5 Wh back to the charger) for an
// agent at (0, 0) with 10 of 20 Wh: above the threshold (6 Wh) and the reserve at its cell.
// With the check (1.5 x 15.5 Wh > 10 Wh) it charges first, to 20 Wh, then does the task
// without dropping it. Without, it sets out and hands the task back at x = 8 (the reserve
// trips: 6 Wh < 1.5 x 4.5 Wh), having driven 16 m for nothing.
TEST(Battery, AnAgentThatCannotAffordATaskAndTheWayToAChargerChargesBeforeItTakesIt)
{
  const planner::Graph g = ttest::grid({"................", ".###############"});
  auto file = ttest::task_file(g, {{{15, 0}, {14, 0}}});
  for (bool check : {true, false}) {
    SCOPED_TRACE(check ? "task check" : "no task check");
    auto tm = std::make_unique<TaskPool>(file, g, 1, std::make_unique<GreedyAssigner>());
    BatteryOptions o;
    o.capacity_wh = 20;
    o.initial = 0.5;
    o.per_m_wh = 0.5;
    o.threshold = 0.3;
    o.critical = 0.1;
    o.target = 1.0;
    o.task_check = check;
    tm->set_battery(g, o, {{g.at(0, 1), 4.0, "c"}}, centres(g));
    Config at{g.at(0, 0)};
    tm->start(at);
    EXPECT_EQ(tm->busy(0), !check);
    EXPECT_EQ(tm->charging(0), check);
    long finished_at = -1;
    for (long t = 1; t <= 60 && finished_at < 0; ++t) {
      at[0] = step_to_goal(g, at[0], tm->goals()[0]);
      tm->update(t, at);
      if (tm->tasks_finished() > 0) finished_at = t;
    }
    EXPECT_EQ(tm->battery()->ran_empty(), 0);
    if (check) {
      // 1 step onto the charger, 2 more charging (4 Wh a step), 17 moves (out of the stub,
      // to x = 15, back to x = 14).
      EXPECT_EQ(tm->dropped_for_charge(), 0);
      EXPECT_EQ(finished_at, 21);
    } else {
      // Out to x = 8 (8 steps), back onto the charger (9), 4 more charging, then the 17 moves.
      EXPECT_EQ(tm->dropped_for_charge(), 1);
      EXPECT_EQ(finished_at, 39);
    }
  }
}

TEST(Battery, ARoundRobinAgentThatCannotAffordItsNextTaskChargesBeforeItTakesIt)
{
  // As above, with the task fixed by round-robin: the task check defers it until the agent
  // has charged; without the check the agent sets off and hands it back halfway.
  const planner::Graph g = ttest::grid({"................", ".###############"});
  auto file = ttest::task_file(g, {{{15, 0}, {14, 0}}});
  for (bool check : {true, false}) {
    SCOPED_TRACE(check ? "task check" : "no task check");
    RoundRobin rr(file);
    BatteryOptions o;
    o.capacity_wh = 20;
    o.initial = 0.5;
    o.per_m_wh = 0.5;
    o.threshold = 0.3;
    o.critical = 0.1;
    o.target = 1.0;
    o.task_check = check;
    rr.set_battery(g, o, {{g.at(0, 1), 4.0, "c"}}, centres(g));
    Config at{g.at(0, 0)};
    rr.start(at);
    EXPECT_EQ(rr.busy(0), !check);
    EXPECT_EQ(rr.charging(0), check);
    long finished_at = -1;
    for (long t = 1; t <= 60 && finished_at < 0; ++t) {
      at[0] = step_to_goal(g, at[0], rr.goals()[0]);
      rr.update(t, at);
      if (rr.tasks_finished() > 0) finished_at = t;
    }
    EXPECT_EQ(rr.battery()->ran_empty(), 0);
    EXPECT_EQ(rr.dropped_for_charge(), check ? 0 : 1);
    EXPECT_EQ(finished_at, check ? 21 : 39);
    // Its next task (the same line, the file has one) is checked the same way at (14, 0).
  }
}
