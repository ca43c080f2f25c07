// ErrandStalls (tasks/errand_stalls.hpp): open ticks and stall ticks of errands, with
// agents moved by hand so that every number is exact.
#include <gtest/gtest.h>

#include "tasks/errand_stalls.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/task_pool.hpp"
#include "tasks/urgency.hpp"
#include "tasks/greedy_assigner.hpp"
#include "tasks/stub_mouths.hpp"
#include "planner/dist_table.hpp"

#include <algorithm>
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

// Stall handover (UrgencyOptions::swap_after, task_pool.hpp): two agents head for one
// pick-up cell at x = 0; B moves once (its errand makes progress), A never does. At step
// T = 5 A's errand has stalled 5 ticks and B's 4, and B is nearer: B takes A's task and A
// B's, their goals unchanged. The errand then makes progress with B's next move.
TEST(ErrandStalls, AStalledErrandPassesToANearerAgentHeadingForTheSameCell)
{
  const planner::Graph g = ttest::grid({".........."});
  auto file = ttest::task_file(g, {{{0, 0}, {9, 0}}, {{0, 0}, {8, 0}}});
  for (int T : {5, 0}) {
    SCOPED_TRACE("swap_after " + std::to_string(T));
    TaskPool tm(file, g, 2, std::make_unique<GreedyAssigner>());
    UrgencyOptions u;
    u.swap_after = T;
    tm.set_urgency(u);
    tm.watch_stalls(g);
    const int A = 0, B = 1;
    Config at{g.at(6, 0), g.at(3, 0)};
    tm.start(at);
    ASSERT_TRUE(tm.busy(A) && tm.busy(B));
    const long a_task = tm.task_of(A)->id, b_task = tm.task_of(B)->id;
    at[B] = g.at(2, 0);
    for (long t = 1; t <= 5; ++t) {
      tm.update(t, at);
      if (t < 5) {
        EXPECT_EQ(tm.task_of(A)->id, a_task) << "step " << t;
      }
    }
    EXPECT_EQ(tm.goals(), (Config{g.at(0, 0), g.at(0, 0)}));  // nobody's goal changed
    if (T == 0) {
      EXPECT_EQ(tm.task_of(A)->id, a_task);
      EXPECT_EQ(tm.handovers(), 0);
      continue;
    }
    EXPECT_EQ(tm.task_of(B)->id, a_task);
    EXPECT_EQ(tm.task_of(A)->id, b_task);
    EXPECT_EQ(tm.handovers(), 1);
    EXPECT_EQ(tm.stalls()->stalled(5, a_task), 5);  // a new holder: no progress yet
    at[B] = g.at(1, 0);
    tm.update(6, at);
    EXPECT_EQ(tm.stalls()->stalled(6, a_task), 0);  // B got closer
    EXPECT_EQ(tm.task_of(B)->id, a_task);           // and keeps it
  }
}

// Head hints (UrgencyOptions::head_after): a dead-end pocket (1, 2) with a pick-up station,
// below a loop of aisles; the drop station (0, 1) is on the loop. Agent 0 starts on the
// pick-up station, picks up at step 1 and must leave: it gets kLeavingUrgency. Agents 1
// (never moves) and 2 (one move closer at step 1) head for the pick-up station from the
// loop: at step 3 only the most stalled, agent 1, gets a hint (its 3 stall ticks); agent 2
// (2 ticks) none. Off (head_after 0): no hints at all.
TEST(ErrandStalls, HeadHintsGoToTheMostStalledAgentPerCellAndToAgentsLeavingAPocket)
{
  const planner::Graph g = ttest::grid({".....", "..#..", "#.###"});
  auto file = ttest::task_file(g, {{{1, 2}, {0, 1}}, {{1, 2}, {0, 1}}, {{1, 2}, {0, 1}}});
  for (int H : {2, 0}) {
    SCOPED_TRACE("head_after " + std::to_string(H));
    TaskPool tm(file, g, 3, std::make_unique<GreedyAssigner>());
    UrgencyOptions u;
    u.head_after = H;
    tm.set_urgency(u);
    tm.watch_stalls(g);
    Config at{g.at(1, 2), g.at(4, 0), g.at(4, 1)};
    tm.start(at);
    EXPECT_EQ(tm.pocket(g.at(1, 2)), g.at(1, 2));
    EXPECT_EQ(tm.pocket(g.at(1, 1)), -1);  // a junction
    EXPECT_EQ(tm.pocket(g.at(3, 0)), -1);
    at[2] = g.at(3, 1);
    for (long t = 1; t <= 3; ++t) tm.update(t, at);
    ASSERT_EQ(tm.goals()[0], g.at(0, 1));  // picked up: on its way out
    const std::vector<float> h = priority_hints(tm, &at);
    if (H == 0) {
      EXPECT_TRUE(h.empty());
      continue;
    }
    ASSERT_EQ(h.size(), 3u);
    EXPECT_EQ(h[0], kLeavingUrgency);
    EXPECT_EQ(h[1], 3.0f);
    EXPECT_EQ(h[2], 0.0f);
  }
}

// Leaving a pocket outranks battery urgency, also for a low agent (session 42). The head-hint
// map with batteries: every agent starts at 31 of 100 Wh (threshold 30), and a move drains 2
// Wh. Agent 0 steps from the junction (1, 1) into the pick-up pocket at step 1 (29 Wh: low),
// picks up and must leave; agent 1 steps toward the station (low, heading). Agent 0's hint is
// kLeavingUrgency, above agent 1's battery hint. Before, the battery hint overwrote the leaving
// one and leavers (5000) ranked below low agents: on the large warehouse with 16 charger stubs
// low AGVs pushed into the stubs past the ones that had to leave, and the fleet jammed.
TEST(ErrandStalls, LeavingAPocketOutranksBatteryUrgency)
{
  const planner::Graph g = ttest::grid({".....", "..#..", "#.###"});
  auto file = ttest::task_file(g, {{{1, 2}, {0, 1}}, {{1, 2}, {0, 1}}, {{1, 2}, {0, 1}}});
  TaskPool tm(file, g, 3, std::make_unique<GreedyAssigner>());
  UrgencyOptions u;
  u.head_after = 100;  // head hints on (leavers), no agent stalls that long here
  u.battery = true;
  tm.set_urgency(u);
  BatteryOptions b;
  b.initial = 0.31;
  b.per_m_wh = 2;
  b.threshold = 0.3;
  b.critical = 0;
  b.reserve_margin = 0;
  tm.set_grid_battery(g, b, {g.at(0, 0)}, 7200);
  tm.watch_stalls(g);
  Config at{g.at(1, 1), g.at(4, 0), g.at(4, 1)};
  tm.start(at);
  ASSERT_TRUE(tm.busy(0) && tm.busy(1));
  ASSERT_EQ(tm.goals()[0], g.at(1, 2));
  at[0] = g.at(1, 2), at[1] = g.at(3, 0);
  tm.update(1, at);
  ASSERT_EQ(tm.goals()[0], g.at(0, 1));  // picked up: on its way out of the pocket
  ASSERT_TRUE(tm.battery()->low(0) && tm.battery()->low(1));
  const std::vector<float> h = priority_hints(tm, &at);
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[0], kLeavingUrgency);
  EXPECT_GE(h[1], kBatteryUrgency);  // low and heading for its station
  EXPECT_GT(h[0], h[1]);
}

// Drop hints (UrgencyOptions::drop_hints): agents 0-2 pick up where they stand at step 1
// and then, one cell on, stall on their way to the same drop cell (4, 1); agents 3 and 4 stall on their way
// to the same pick-up cell (4, 0). An open 3 x 5 grid: no pocket. Off, each cell's crowd has
// one head (the most stalled, ties to the lower index): agents 0 and 3. With drop hints,
// every stalled agent with a load on board gets its stall; the pick-up crowd keeps one head.
TEST(ErrandStalls, DropHintsGoToEveryStalledAgentWithALoad)
{
  const planner::Graph g = ttest::grid({".....", ".....", "....."});
  auto file = ttest::task_file(g, {{{0, 0}, {4, 1}}, {{0, 1}, {4, 1}}, {{0, 2}, {4, 1}},
                                   {{4, 0}, {4, 1}}, {{4, 0}, {4, 1}}});
  for (bool on : {true, false}) {
    SCOPED_TRACE(on ? "drop_hints on" : "drop_hints off");
    TaskPool tm(file, g, 5, std::make_unique<GreedyAssigner>());
    UrgencyOptions u;
    u.head_after = 2;
    u.drop_hints = on;
    tm.set_urgency(u);
    tm.watch_stalls(g);
    Config at{g.at(0, 0), g.at(0, 1), g.at(0, 2), g.at(2, 0), g.at(2, 2)};
    tm.start(at);
    tm.update(1, at);
    for (int a = 0; a < 3; ++a) at[a] = g.at(1, a);  // off the errand cells (pockets: see above)
    for (long t = 2; t <= 6; ++t) tm.update(t, at);
    for (int a = 0; a < 3; ++a) ASSERT_EQ(tm.goals()[a], g.at(4, 1)) << a;  // picked up
    for (int a = 3; a < 5; ++a) ASSERT_EQ(tm.goals()[a], g.at(4, 0)) << a;
    const std::vector<float> h = priority_hints(tm, &at);
    ASSERT_EQ(h.size(), 5u);
    EXPECT_GE(h[0], 2.0f);
    EXPECT_EQ(h[1], on ? h[0] : 0.0f);
    EXPECT_EQ(h[2], on ? h[0] : 0.0f);
    EXPECT_GE(h[3], 2.0f);
    EXPECT_EQ(h[4], 0.0f);
  }
}

// Station load (UrgencyOptions::load_cost): agent 0 holds a task at (0, 0); agent 1 finishes
// its task at (3, 0) and is matched again: the free task at (0, 0) is 3 moves away, the one
// at (7, 0) 4. Off, it takes the nearer; with load_cost 10 the (0, 0) task costs 3 + 10 x 1
// (one task already held there), and it takes the one at (7, 0).
TEST(ErrandStalls, StationLoadSteersTheMatchingToAStationNobodyIsBoundFor)
{
  const planner::Graph g = ttest::grid({".........."});
  auto file = ttest::task_file(g, {{{0, 0}}, {{3, 0}}, {{0, 0}}, {{7, 0}}});
  for (int w : {10, 0}) {
    SCOPED_TRACE("load_cost " + std::to_string(w));
    TaskPool tm(file, g, 3, std::make_unique<GreedyAssigner>());
    UrgencyOptions u;
    u.load_cost = w;
    tm.set_urgency(u);
    const Config at{g.at(1, 0), g.at(3, 0)};
    tm.start(at);
    ASSERT_EQ(tm.goals()[0], g.at(0, 0));
    ASSERT_EQ(tm.goals()[1], g.at(3, 0));
    tm.update(1, at);  // agent 1 done; task 3 (7, 0) revealed
    EXPECT_EQ(tm.goals()[1], w > 0 ? g.at(7, 0) : g.at(0, 0));
  }
}

// Stub mouths (tasks/stub_mouths.hpp): a station-side aisle y = 2 with five one-cell stubs
// below it (stations at x = 1, 3, 5, 7, 9 on y = 3) and a parallel aisle y = 0 without
// stations. From (0, 2) to the far station (9, 3) the station-side aisle is shorter (10
// moves against 15 round by y = 0), so without the cost the tables send the AGV past four
// other stations' mouths; with mouth_cost 4 each mouth costs 5 and the route by y = 0 is
// shorter: PIBT's best first move from (0, 2) is up, not along the stations.
TEST(ErrandStalls, MouthCostRoutesThroughTrafficAwayFromOtherStationsStubs)
{
  planner::Graph g = ttest::grid({"...........",
                                  ".#########.",
                                  "...........",
                                  "#.#.#.#.#.#"});
  std::vector<Vertex> stations;
  for (int x = 1; x <= 9; x += 2) stations.push_back(g.at(x, 3));
  stations.push_back(g.at(5, 0));  // on an aisle, not at a dead end: no mouth
  std::vector<Vertex> mouths = stub_mouths(g, stations);
  std::sort(mouths.begin(), mouths.end());
  std::vector<Vertex> want;
  for (int x = 1; x <= 9; x += 2) want.push_back(g.at(x, 2));
  std::sort(want.begin(), want.end());
  EXPECT_EQ(mouths, want);

  const Vertex goal = g.at(9, 3);
  auto dist = [&](int x, int y) {
    planner::DistTable d(g);
    d.set_goals({goal});
    return d.get(0, g.at(x, y));
  };
  EXPECT_LT(dist(1, 2), dist(0, 1));  // no costs: along the stations
  const std::vector<uint8_t> off = mouth_costs(g, stations, 0);
  EXPECT_TRUE(std::all_of(off.begin(), off.end(), [](uint8_t c) { return c == 1; }));
  g.set_move_costs(mouth_costs(g, stations, 4));
  EXPECT_EQ(g.move_cost(g.at(3, 2)), 5);
  EXPECT_EQ(g.move_cost(g.at(2, 2)), 1);
  EXPECT_LT(dist(0, 1), dist(1, 2));  // up to the aisle without stations
  EXPECT_EQ(dist(0, 1), 13 + 5 + 1);  // 13 moves to (10, 2), its own mouth (9, 2), the station
}

// Sticky stalls (UrgencyOptions::sticky, ErrandStalls::set_sticky): an errand that stood 6
// steps and then moved a cell keeps reading 6, not 0, so its holder keeps the priority it
// had earned instead of falling behind every newer stalled errand; a later, longer stall
// reads as itself. Off: the current stall only.
TEST(ErrandStalls, StickyStallsKeepAnErrandsLongestStallAfterItMoves)
{
  const planner::Graph g = ttest::grid({".........."});
  for (bool sticky : {false, true}) {
    SCOPED_TRACE(sticky ? "sticky" : "not sticky");
    ErrandStalls s(g);
    s.set_sticky(sticky);
    const std::vector<ErrandStalls::Held> held{{7, 0, g.at(9, 0)}};
    const std::vector<int> xs{0, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2};  // mark at 1, stands 2..7, mark at 8
    for (long t = 0; t < static_cast<long>(xs.size()); ++t) s.observe(t, held, Config{g.at(xs[t], 0)});
    EXPECT_EQ(s.stalled(10, 7), sticky ? 7 : 2);  // longest gap 1 -> 8 = 7; now 2 since the mark at 8
    for (long t = 11; t < 20; ++t) s.observe(t, held, Config{g.at(2, 0)});
    EXPECT_EQ(s.stalled(19, 7), 11);  // the current stall is the longest: both read it
  }
}
