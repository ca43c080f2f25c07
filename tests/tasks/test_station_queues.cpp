// Station queues and parking (tasks/station_queues.hpp, tasks/parking.hpp): the queue's
// layout at a dead-end station, admission in order, and whole lifelong runs in which no
// more than `capacity` agents head for a station and idle agents end on parking cells.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "tasks/escalation.hpp"
#include "tasks/greedy_assigner.hpp"
#include "tasks/lifelong_run.hpp"
#include "planner/output_file.hpp"
#include "tasks/parking.hpp"
#include "tasks/queue_trace.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/station_queues.hpp"
#include "tasks/task_pool.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;
using planner::Config;
using planner::Vertex;

namespace {

// A dead-end station S at the top of a 2-cell stub off a cross aisle; below the stub's
// mouth a picking aisle (4 cells) leads to a second cross aisle.
//   y0  ###S##
//   y1  ###.##
//   y2  ......   <- mouth (3, 2)
//   y3..y6 ###.##
//   y7  ......
const planner::Graph& stub()
{
  static const planner::Graph g = ttest::grid({"###.##", "###.##", "......", "###.##", "###.##", "###.##", "###.##", "......"});
  return g;
}

// One step of the task manager as the queues see it: every agent's goal is its errand cell,
// an idle agent's the cell it stands on; then the queues re-place them (goals, unplaced).
void apply_queues(StationQueues& q, const std::vector<Vertex>& errand, const Config& pos, Config& goals,
                  std::vector<char>& unplaced)
{
  for (size_t a = 0; a < pos.size(); ++a) goals[a] = errand[a] >= 0 ? errand[a] : pos[a];
  q.apply(errand, pos, goals, unplaced);
}

}  // namespace

TEST(StationQueues, ADeadEndStationQueuesBesideItsMouthAlongTheLongestAisle)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  StationQueues q(g, {s, s}, {1, 4, 0});
  ASSERT_EQ(q.num_stations(), 1);
  EXPECT_EQ(q.station(0), s);
  // Not in the pocket (the stub) nor on its mouth, where the AGV leaving would meet it; down
  // the picking aisle (4 corridor cells) rather than along the cross aisle (2 east, 3 west).
  EXPECT_EQ(q.queue_cells(0), (std::vector<Vertex>{g.at(3, 3), g.at(3, 4), g.at(3, 5), g.at(3, 6)}));
  for (Vertex v : {g.at(3, 0), g.at(3, 1), g.at(3, 2), g.at(3, 3), g.at(3, 6)}) EXPECT_TRUE(q.reserved(v)) << v;
  for (Vertex v : {g.at(2, 2), g.at(4, 2), g.at(3, 7)}) EXPECT_FALSE(q.reserved(v)) << v;
  EXPECT_EQ(q.admission_limit(0), 5);  // capacity + queue cells
  // The chain stops where the net has no more room.
  StationQueues longer(g, {s}, {1, 20, 0});
  EXPECT_EQ(longer.queue_cells(0).size(), 8u);  // the aisle, the cross-aisle junction (3, 7), then west (3 cells)
}

TEST(StationQueues, AdmitsTheNearestQueuesTheRestAndLetsTheNextInWhenTheWayIsClear)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  StationQueues q(g, {s}, {1, 3, 0});
  const std::vector<Vertex> qc = q.queue_cells(0);
  ASSERT_EQ(qc.size(), 3u);
  // Five agents with an errand at S, one idle.
  Config pos{g.at(0, 7), g.at(5, 2), g.at(0, 2), g.at(5, 7), g.at(3, 7), g.at(1, 7)};
  std::vector<Vertex> errand{s, s, s, s, s, -1};
  Config goals(6);
  // The task manager's goals (errand cells, idle agents where they stand), then the queues.
  std::vector<char> unplaced;
  auto apply = [&] { apply_queues(q, errand, pos, goals, unplaced); };
  apply();
  // Distances to S: a1 4, a2 5, a4 7, a3 9, a0 10: a1 admitted, a2, a4, a3 queued in that
  // order, a0 beyond the queue is unplaced (its goal is the caller's); the idle agent is untouched.
  EXPECT_EQ(goals, (Config{s, s, qc[0], qc[2], qc[1], g.at(1, 7)}));
  EXPECT_EQ(unplaced, (std::vector<char>{1, 0, 0, 0, 0, 0}));
  EXPECT_EQ(q.admitted(0), (std::vector<int>{1}));
  EXPECT_EQ(q.waiting(0), (std::vector<int>{2, 4, 3}));

  // a1 reaches S and completes (no errand left): while it stands in the stub nobody else
  // is let in, whoever is nearer.
  pos[1] = s;
  pos[3] = g.at(3, 2);
  errand[1] = -1;
  apply();
  EXPECT_TRUE(q.admitted(0).empty());
  EXPECT_EQ(goals[2], qc[0]);
  pos[1] = g.at(3, 1);
  apply();
  EXPECT_TRUE(q.admitted(0).empty());
  // Out of the stub: the queue moves up by one, in its order; a0 joins its end.
  pos[1] = g.at(3, 2);
  apply();
  EXPECT_EQ(q.admitted(0), (std::vector<int>{2}));
  EXPECT_EQ(q.waiting(0), (std::vector<int>{4, 3, 0}));
  EXPECT_EQ(goals[2], s);
  EXPECT_EQ(goals[4], qc[0]);
  EXPECT_EQ(goals[3], qc[1]);
  EXPECT_EQ(goals[0], qc[2]);
}

// Beyond the queue, first asked first taken: a far agent is not overtaken forever by nearer
// newcomers (with `fifo` off it is: the old nearest-first order starves it).
TEST(StationQueues, BeyondTheQueueTheOldestRequestGoesFirstSoNoErrandWaitsForever)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  // The round in which agent 0 (far away) is admitted; -1: not within the rounds.
  auto admitted_round = [&](bool fifo) {
    QueueOptions o{1, 1, 0};
    o.fifo = fifo;
    StationQueues q(g, {s}, o);
    // a0 at the far end (10 moves from S), a1 and a2 near; a3..a5 come near later.
    Config pos{g.at(0, 7), g.at(4, 2), g.at(5, 2), g.at(1, 2), g.at(2, 2), g.at(0, 2)};
    std::vector<Vertex> errand{s, s, s, -1, -1, -1};
    Config goals(pos.size());
    std::vector<char> unplaced;
    auto apply = [&] { apply_queues(q, errand, pos, goals, unplaced); };
    apply();
    EXPECT_EQ(q.admitted(0), (std::vector<int>{1}));
    EXPECT_EQ(unplaced[0], 1);
    for (int r = 1; r <= 3; ++r) {
      // The admitted agent completes and leaves; a newcomer nearer than a0 asks.
      const int done = q.admitted(0).front();
      errand[done] = -1;
      pos[done] = g.at(1 + r, 7);
      errand[2 + r] = s;
      apply();
      if (q.admitted(0) == std::vector<int>{0}) return r;
    }
    return -1;
  };
  EXPECT_EQ(admitted_round(true), 2);    // queued in round 1 (before a3), in at round 2
  EXPECT_EQ(admitted_round(false), -1);  // nearest first: a3, a4, a5 each overtake it
}

namespace {

struct QueueRun {
  long errands = 0;
  int max_heading = 0;   // most agents heading for S at once
  long queued_ticks = 0; // agent-steps standing on their queue cell, waiting
};

// Six agents, tasks alternating S -> a drop at either end of the bottom aisle.
QueueRun run_station(int capacity)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  auto file = ttest::task_file(g, {{{3, 0}, {0, 7}}, {{3, 0}, {5, 7}}});
  TaskPool pool(file, g, 6, std::make_unique<GreedyAssigner>());
  pool.set_queues(g, {capacity, 3, 0});
  const Config starts{g.at(0, 2), g.at(5, 2), g.at(1, 7), g.at(4, 7), g.at(0, 7), g.at(5, 7)};
  LifelongOptions opt;
  opt.steps = 300;
  opt.budget = planner::Budget::expansion_count(50);
  LifelongRun run(g, starts, pool, "rtlacam", 0, opt);
  QueueRun r;
  std::vector<Vertex> queue_cells;
  if (pool.queues()) queue_cells = pool.queues()->queue_cells(0);
  while (!run.done()) {
    run.step();
    const Config& pos = run.planner().current();
    int heading = 0;
    for (int a = 0; a < pool.num_agents(); ++a) {
      if (pool.heading(a) && pool.goals()[a] == s) ++heading;
      if (pool.busy(a) && !pool.heading(a) && pos[a] == pool.goals()[a] &&
          std::find(queue_cells.begin(), queue_cells.end(), pos[a]) != queue_cells.end())
        ++r.queued_ticks;
    }
    r.max_heading = std::max(r.max_heading, heading);
  }
  r.errands = pool.errands_finished();
  EXPECT_EQ(run.finish().planner_errors, 0);
  return r;
}

}  // namespace

TEST(StationQueues, ALifelongRunSendsAtMostCapacityAgentsToTheStationAndTheRestWaitOnQueueCells)
{
  const QueueRun r = run_station(1);
  EXPECT_LE(r.max_heading, 1);
  EXPECT_GT(r.queued_ticks, 50);
  // Each visit needs the one before out of the stub first: it still flows.
  EXPECT_GE(r.errands, 30);
}

TEST(Parking, IdleAgentsEndOnParkingCells)
{
  const auto& g = stub();
  // One task at a time in the pool for four agents: three are always idle.
  auto file = ttest::task_file(g, {{{0, 2}, {5, 2}}, {{5, 2}, {0, 2}}});
  TaskPool pool(file, g, 1, std::make_unique<GreedyAssigner>());
  const std::vector<Vertex> park{g.at(3, 3), g.at(3, 4), g.at(3, 5), g.at(3, 6)};
  pool.set_parking(g, park);
  const Config starts{g.at(3, 0), g.at(0, 7), g.at(5, 7), g.at(2, 2)};
  LifelongOptions opt;
  opt.steps = 80;
  opt.budget = planner::Budget::expansion_count(50);
  LifelongRun run(g, starts, pool, "rtlacam", 0, opt);
  while (!run.done()) run.step();
  const Config& pos = run.planner().current();
  int idle = 0;
  for (int a = 0; a < pool.num_agents(); ++a) {
    if (pool.busy(a)) continue;
    ++idle;
    EXPECT_NE(std::find(park.begin(), park.end(), pos[a]), park.end()) << "agent " << a << " idle at " << pos[a];
  }
  EXPECT_GE(idle, 3);
  EXPECT_GE(pool.errands_finished(), 4);
  EXPECT_EQ(run.finish().planner_errors, 0);
}

// Pocket clearing (QueueOptions::clear_after): an agent that must get out of the stub (here
// an idle one on S) with the admitted agent behind it is a deadlock nobody plans out of (in a
// one-lane dead end nobody passes). After clear_after steps with a leaver inside, the station
// gives up its places (its agents are unplaced: they wait like idle agents) and admits again,
// in the old order, once the stub is empty. Off (clear_after 0), the admitted agent stays.
TEST(StationQueues, AStationWhosePocketHoldsALeaverTooLongGivesUpItsPlacesUntilItIsEmpty)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  for (int clear_after : {0, 3}) {
    StationQueues q(g, {s}, {1, 3, 0, true, clear_after});
    // a0 idle, a1 and a2 with an errand at S.
    Config pos{g.at(4, 2), g.at(3, 3), g.at(3, 7)};
    std::vector<Vertex> errand{-1, s, s};
    Config goals(3);
    std::vector<char> unplaced;
    auto apply = [&] { apply_queues(q, errand, pos, goals, unplaced); };
    apply();
    ASSERT_EQ(q.admitted(0), (std::vector<int>{1}));
    EXPECT_EQ(q.waiting(0), (std::vector<int>{2}));
    // a0 pushed onto S, a1 behind it in the stub: wedged.
    pos[0] = s;
    pos[1] = g.at(3, 1);
    for (int k = 0; k < 2; ++k) apply();
    EXPECT_EQ(q.admitted(0), (std::vector<int>{1})) << clear_after;  // not yet
    apply();
    if (clear_after == 0) {
      EXPECT_EQ(q.admitted(0), (std::vector<int>{1}));
      EXPECT_EQ(q.clearings(), 0);
      continue;
    }
    EXPECT_TRUE(q.admitted(0).empty());
    EXPECT_TRUE(q.waiting(0).empty());
    EXPECT_EQ(unplaced, (std::vector<char>{0, 1, 1}));  // the caller parks them (off the stub)
    EXPECT_EQ(q.clearings(), 1);
    EXPECT_TRUE(q.clearing(0));  // leavers_first's test (urgency.cpp)
    // a1 backs out; a0 still inside: nobody is let in.
    pos[1] = g.at(3, 3);
    apply();
    EXPECT_TRUE(q.admitted(0).empty());
    EXPECT_EQ(unplaced, (std::vector<char>{0, 1, 1}));
    // a0 out: a1 (the older request) is admitted again, a2 queued.
    pos[0] = g.at(4, 2);
    apply();
    EXPECT_EQ(q.admitted(0), (std::vector<int>{1}));
    EXPECT_EQ(q.waiting(0), (std::vector<int>{2}));
    EXPECT_EQ(goals[1], s);
    EXPECT_EQ(q.clearings(), 1);
    EXPECT_FALSE(q.clearing(0));
    EXPECT_EQ(q.longest_clearing(), 2);  // the apply() calls with the places given up
    EXPECT_EQ(q.clearing_steps(), 2);
  }
}

// Jam clearing (QueueOptions::jam_after): an admitted agent outside the stub that comes no
// nearer to its station for jam_after steps (here: an intruder stands in the one-wide queue
// lane, nobody passes) makes the station give up its places; its agents wait unplaced (the
// caller parks them off the lane) until the stub, mouth and queue cells are empty, or for
// jam_after steps at most, and are then let in again in the old order. An admitted agent
// that keeps coming nearer never triggers it. Off (jam_after 0), the places stay.
TEST(StationQueues, AStationWhoseAdmittedAgentMakesNoProgressGivesUpItsPlacesUntilItsLaneIsEmpty)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  for (int jam_after : {0, 3})
    for (bool intruder_leaves : {true, false}) {
      QueueOptions o{1, 4, 0, true, 0};
      o.jam_after = jam_after;
      StationQueues q(g, {s}, o);
      ASSERT_EQ(q.queue_cells(0), (std::vector<Vertex>{g.at(3, 3), g.at(3, 4), g.at(3, 5), g.at(3, 6)}));
      // a0 idle in the lane, a1 below it (admitted), a2 farther off (queued).
      Config pos{g.at(3, 4), g.at(3, 7), g.at(0, 7)};
      std::vector<Vertex> errand{-1, s, s};
      Config goals(3);
      std::vector<char> unplaced;
      auto apply = [&] { apply_queues(q, errand, pos, goals, unplaced); };
      for (int k = 0; k < 4; ++k) apply();
      ASSERT_EQ(q.admitted(0), (std::vector<int>{1}));
      EXPECT_EQ(q.waiting(0), (std::vector<int>{2}));
      apply();  // a1 watched since the 2nd call: 3 calls without coming nearer
      if (jam_after == 0) {
        EXPECT_EQ(q.admitted(0), (std::vector<int>{1}));
        EXPECT_EQ(q.clearings(), 0);
        continue;
      }
      EXPECT_TRUE(q.admitted(0).empty());
      EXPECT_TRUE(q.waiting(0).empty());
      EXPECT_EQ(unplaced, (std::vector<char>{0, 1, 1}));
      EXPECT_EQ(q.clearings(), 1);
      EXPECT_EQ(q.jam_clearings(), 1);
      EXPECT_TRUE(q.clearing(0));
      if (intruder_leaves) {
        apply();
        EXPECT_TRUE(q.clearing(0));  // a0 still in the lane
        pos[0] = g.at(0, 2);
        apply();  // the lane is empty: a1 (the older request) first again
      } else {
        for (int k = 0; k < 2; ++k) apply();
        EXPECT_TRUE(q.clearing(0));
        apply();  // jam_after calls: the places come back though a0 stayed
      }
      EXPECT_FALSE(q.clearing(0)) << intruder_leaves;
      EXPECT_EQ(q.admitted(0), (std::vector<int>{1}));
      EXPECT_EQ(q.waiting(0), (std::vector<int>{2}));
      EXPECT_EQ(goals[2], g.at(3, 3));
    }
  // Progress resets the watch: a1 one cell nearer every second call never jams.
  QueueOptions o{1, 4, 0, true, 0};
  o.jam_after = 3;
  StationQueues q(g, {s}, o);
  Config pos{g.at(0, 2), g.at(0, 7), g.at(5, 7)};
  const std::vector<Vertex> path{g.at(1, 7), g.at(2, 7), g.at(3, 7), g.at(3, 6), g.at(3, 5), g.at(3, 4)};
  Config goals(3);
  std::vector<char> unplaced;
  for (size_t k = 0; k < 2 * path.size(); ++k) {
    if (k % 2 == 1) pos[1] = path[k / 2];
    for (int a = 0; a < 3; ++a) goals[a] = a == 1 ? s : pos[a];
    q.apply({-1, s, -1}, pos, goals, unplaced);
  }
  EXPECT_EQ(q.clearings(), 0);
  EXPECT_EQ(q.admitted(0), (std::vector<int>{1}));
}

// One-way queue lanes (QueueOptions::one_way): on a lane cell the only move is towards the
// station, the mouth no longer leads into the lane, and the lane is entered from its far end;
// every other arc stays. A lane that is the only way between two parts of the net is refused.
TEST(StationQueues, OneWayQueueLanesLeadOnlyTowardsTheStation)
{
  // stub() with a second picking aisle at x = 6: the way down once the lane at x = 3 is one-way.
  const planner::Graph g = ttest::grid({"###.####", "###.####", "........", "###.##.#", "###.##.#", "###.##.#", "###.##.#", "........"});
  const Vertex s = g.at(3, 0);
  QueueOptions o{1, 4};
  const StationQueues q(g, {s}, o);
  ASSERT_EQ(q.queue_cells(0), (std::vector<Vertex>{g.at(3, 3), g.at(3, 4), g.at(3, 5), g.at(3, 6)}));
  ASSERT_EQ(q.mouth(0), g.at(3, 2));
  const planner::Graph d = one_way_queue_lanes(g, {s}, o);
  auto arc = [&](int x0, int y0, int x1, int y1) { return d.adjacent(d.at(x0, y0), d.at(x1, y1)); };
  EXPECT_TRUE(arc(3, 3, 3, 2));   // q1 -> mouth
  EXPECT_FALSE(arc(3, 2, 3, 3));  // mouth -> q1: no way up the lane from the mouth
  EXPECT_TRUE(arc(3, 4, 3, 3));
  EXPECT_FALSE(arc(3, 3, 3, 4));
  EXPECT_TRUE(arc(3, 7, 3, 6));   // into the lane from its far end
  EXPECT_FALSE(arc(3, 6, 3, 7));
  EXPECT_TRUE(arc(3, 1, 3, 2) && arc(3, 2, 3, 1));  // the stub and the aisles stay two-way
  EXPECT_TRUE(arc(6, 3, 6, 4) && arc(6, 4, 6, 3));
  EXPECT_TRUE(d.directed());
  EXPECT_EQ(d.num_one_way(), 5u);
  EXPECT_TRUE(d.reaches(g.at(3, 2), g.at(3, 7)));  // down by the other aisle
  EXPECT_TRUE(d.reaches(g.at(3, 7), s));
  // stub() alone: the lane is the only way between the two cross aisles.
  try {
    one_way_queue_lanes(stub(), {s}, o);
    ADD_FAILURE() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cuts the net"), std::string::npos) << e.what();
  }
}

// A parking cell on the cells of a station in use (its queue laid along a parking lane) is not
// used, and an agent parked there leaves: it would block the queue it stands on. While the
// station is idle the cell is a parking cell like any other.
TEST(Parking, AParkingCellOnTheQueueOfAStationInUseIsNotUsed)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  StationQueues q(g, {s}, {1, 4, 0});  // queue cells (3, 3)..(3, 6)
  ASSERT_TRUE(q.reserved(g.at(3, 3)));
  Parking p(g, {g.at(3, 3), g.at(0, 7)});
  // Nobody at the station: the idle agent on the mouth (reserved: it must leave) parks on the
  // nearest parking cell, the first queue cell.
  Config pos{g.at(3, 2), g.at(5, 7)};
  Config goals = pos;
  std::vector<char> unplaced;
  q.apply({-1, -1}, pos, goals, unplaced);
  EXPECT_FALSE(q.in_use_cells()[g.at(3, 3)]);
  p.apply({1, 0}, pos, &q.reserved_cells(), goals, &q.in_use_cells());
  EXPECT_EQ(goals[0], g.at(3, 3));
  // Agent 1 gets an errand at the station: its queue is in use, the parked agent moves on.
  pos[0] = g.at(3, 3);
  goals = pos;
  q.apply({-1, s}, pos, goals, unplaced);
  EXPECT_TRUE(q.in_use_cells()[g.at(3, 3)]);
  EXPECT_TRUE(q.in_use_cells()[g.at(3, 1)]);  // the pocket
  EXPECT_FALSE(q.in_use_cells()[g.at(0, 7)]);
  p.apply({1, 0}, pos, &q.reserved_cells(), goals, &q.in_use_cells());
  EXPECT_EQ(goals[0], g.at(0, 7));
}

// in_line: a queue lane is single file, so the admitted agent and the queue cells go to the
// placed agents in the order they stand (nearest the station first), not in request order.
// Without it the admitted agent stays behind the queued one that stands between it and the
// station (traced on large_warehouse_parking, session 36).
TEST(StationQueues, InLineTheAgentNearestTheStationIsAdmittedFirst)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  QueueOptions o{1, 3, 0};
  for (bool in_line : {true, false}) {
    o.in_line = in_line;
    StationQueues q(g, {s}, o);
    const std::vector<Vertex> qc = q.queue_cells(0);  // (3, 3), (3, 4), (3, 5)
    Config pos{g.at(3, 4), g.at(3, 6), g.at(0, 7)};  // a0 nearest (4 moves), then a1 (6), a2 (10)
    std::vector<Vertex> errand{s, s, s};
    Config goals(3);
    std::vector<char> unplaced;
    q.apply(errand, pos, goals, unplaced);
    ASSERT_EQ(q.admitted(0), (std::vector<int>{0}));
    // a0 and a1 trade places in the lane (a test of the ranking: in a real lane they cannot);
    // a2 comes up between them.
    pos = {g.at(3, 6), g.at(3, 3), g.at(3, 5)};
    goals = errand;  // the task manager's goals: the errand cells
    q.apply(errand, pos, goals, unplaced);
    if (in_line) {
      EXPECT_EQ(q.admitted(0), (std::vector<int>{1}));
      EXPECT_EQ(q.waiting(0), (std::vector<int>{2, 0}));
      EXPECT_EQ(goals, (Config{qc[1], s, qc[0]}));
    } else {  // request order: a0 stays admitted behind a1 and a2
      EXPECT_EQ(q.admitted(0), (std::vector<int>{0}));
      EXPECT_EQ(q.waiting(0), (std::vector<int>{1, 2}));
    }
  }
}

// idle_clear (session 38): an idle agent does not rest beside a dead-end station's mouth, where
// it walls in the AGVs leaving the stub; it rests one cell farther along the cross aisle.
// Without it (the reserved cells only) the agent stays beside the mouth.
TEST(Parking, IdleClearKeepsIdleAgentsOffTheCellsBesideAMouth)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  QueueOptions o{1, 4, 0};
  o.idle_clear = true;
  StationQueues q(g, {s}, o);  // mouth (3, 2); queue cells (3, 3)..(3, 6)
  for (Vertex v : {g.at(2, 2), g.at(4, 2)}) {
    EXPECT_FALSE(q.reserved(v)) << v;
    EXPECT_TRUE(q.clear_cells()[v]) << v;  // beside the mouth
  }
  for (Vertex v : {g.at(1, 2), g.at(5, 2), g.at(0, 7)}) EXPECT_FALSE(q.clear_cells()[v]) << v;
  for (bool on : {true, false}) {
    Parking p(g, {});
    // Agent 0 idle beside the mouth, agent 1 on the mouth (reserved), agent 2 in the far cross aisle.
    Config pos{g.at(2, 2), g.at(3, 2), g.at(0, 7)};
    Config goals = pos;
    p.apply({1, 1, 1}, pos, on ? &q.clear_cells() : &q.reserved_cells(), goals);
    EXPECT_EQ(goals[0], on ? g.at(1, 2) : g.at(2, 2)) << on;
    EXPECT_EQ(goals[1], on ? g.at(5, 2) : g.at(4, 2)) << on;  // off the mouth: not beside it either
    EXPECT_EQ(goals[2], g.at(0, 7)) << on;
  }
}

// The queue trace (output.queue_trace) is a checked write like every output
// (planner/output_file.hpp): a full disk or a missing folder is "cannot write 'PATH': reason",
// never a trace silently cut short.
TEST(QueueTrace, AFailedWriteNamesTheFileAndTheReason)
{
  const auto& g = stub();
  try {
    QueueTrace t("/dev/full", 1, g);  // the header's flush meets a full device
    FAIL() << "no error";
  } catch (const planner::OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write '/dev/full': No space left on device");
  }
  try {
    QueueTrace t("/nonexistent-dir/queue_trace.txt", 1, g);
    FAIL() << "no error";
  } catch (const planner::OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write '/nonexistent-dir/queue_trace.txt': No such file or directory");
  }
}

// Escalation (tasks/escalation.hpp) counts only the steps an errand's holder heads for the
// errand cell: waiting on a queue cell is the station's admission. Before, an errand that
// waited 150 steps in a queue was escalated the moment it was admitted, so at a busy station
// every admitted AGV was (pibt-rot on large_warehouse_queues: 0.31-0.39x the errands at 2000
// ticks; now 0.99x). Two agents, one errand each at S, capacity 1, nobody moves.
TEST(StationQueues, EscalationDoesNotCountTheWaitOnAQueueCell)
{
  const auto& g = stub();
  const Vertex s = g.at(3, 0);
  // Two errands at S, then work at the bottom aisle's east end for whoever is free.
  auto file = ttest::task_file(g, {{{3, 0}}, {{3, 0}}, {{5, 7}}, {{5, 7}}});
  TaskPool pool(file, g, 2, std::make_unique<GreedyAssigner>());
  pool.set_queues(g, {1, 3, 0});
  pool.watch_stalls(g);
  UrgencyOptions u;
  u.escalate_after = 20;
  pool.set_urgency(u);
  Config pos{g.at(0, 2), g.at(1, 2)};
  pool.start(pos);
  const int first = pool.goals()[0] == s ? 0 : 1, second = 1 - first;
  ASSERT_EQ(pool.goals()[first], s);
  ASSERT_NE(pool.goals()[second], s);  // queued
  // Both stand still: the heading one escalates after 20 steps, the queued one never.
  pos[second] = pool.goals()[second];
  for (long t = 1; t <= 30; ++t) pool.update(t, pos);
  EXPECT_TRUE(pool.escalated(first));
  EXPECT_FALSE(pool.escalated(second));
  EXPECT_EQ(escalated_agents(pool), (std::vector<char>{first == 0, first == 1}));
  // The first completes; the second is admitted with 30 steps of stall behind it and is not
  // escalated until it has headed for S 20 steps without getting closer.
  pos[first] = s;
  pool.update(31, pos);
  pos[first] = g.at(5, 7);  // out of the way (its next errand is there)
  for (long t = 32; pool.goals()[second] != s && t < 40; ++t) pool.update(t, pos);
  ASSERT_EQ(pool.goals()[second], s);
  const long admitted = pool.now();
  EXPECT_GT(pool.stalls()->longest(admitted, pool.task_of(second)->id), 20);
  EXPECT_FALSE(pool.escalated(second));
  long t = admitted;
  while (!pool.escalated(second) && t < admitted + 40) pool.update(++t, pos);
  EXPECT_EQ(t - admitted + 1, 20);  // heading steps, the one it was admitted in included
}
