// Adg: type-1 / type-2 edges, rotation groups, release order.
#include <gtest/gtest.h>

#include <random>

#include "executor/adg.hpp"
#include "executor/out_and_back.hpp"
#include "grid.hpp"

using executor::Adg;
using executor::State;

namespace {

// Runs every released action to completion, one at a time, and returns how many finished.
int drain(Adg& adg)
{
  int done = 0;
  for (bool any = true; any;) {
    any = false;
    for (int i = 0; i < adg.num_agents(); ++i) {
      const int id = adg.next_action(i);
      if (id < 0 || !adg.released(id)) continue;
      const std::vector<int> g = adg.group_of(id);
      adg.start(id);
      for (int m : g) {
        adg.finish(m);
        ++done;
      }
      any = true;
    }
  }
  return done;
}

}  // namespace

TEST(Adg, WaitsAreDroppedAndAgentOrderIsKept)
{
  Adg adg({0, 5});
  EXPECT_EQ(adg.append({1, 5}), 1);
  EXPECT_EQ(adg.append({1, 5}), 0);  // all wait: no action
  EXPECT_EQ(adg.append({2, 6}), 2);
  EXPECT_EQ(adg.steps(), 3);
  const int a0 = adg.next_action(0);
  EXPECT_EQ(adg.action(a0).from, 0);
  EXPECT_EQ(adg.action(a0).to, 1);
  const int a1 = a0 + 1;  // agent 0's second move (appended before agent 1's)
  EXPECT_EQ(adg.action(a1).prev, a0);
  EXPECT_FALSE(adg.released(a1));  // type 1: after its first move
  adg.start(a0);
  EXPECT_THROW(adg.start(a0), std::logic_error);
  adg.finish(a0);
  EXPECT_TRUE(adg.released(a1));
  EXPECT_EQ(adg.at(0), 1);
  EXPECT_EQ(adg.progress(0), 2);
  EXPECT_EQ(adg.progress(1), 2);
  EXPECT_EQ(adg.min_progress(), 2);
}

TEST(Adg, FollowingWaitsForTheLeaderToArrive)
{
  // A line 0-1-2-3: agent 0 at 1 follows agent 1 at 2 to the right.
  Adg adg({1, 2});
  adg.append({2, 3});
  const int lead = adg.next_action(1), follow = adg.next_action(0);
  EXPECT_EQ(adg.action(follow).handover, lead);
  EXPECT_TRUE(adg.released(lead));
  EXPECT_FALSE(adg.released(follow));
  adg.start(lead);
  EXPECT_FALSE(adg.released(follow));  // leaving is not enough: it must have arrived
  adg.finish(lead);
  EXPECT_TRUE(adg.released(follow));
}

TEST(Adg, HandOverWaitsForTheLastEarlierOccupant)
{
  // Agent 0 leaves cell 5 at step 0; agent 1 enters it at step 2 even though agent 0 is late.
  Adg adg({5, 3});
  adg.append({6, 3});
  adg.append({6, 4});
  adg.append({6, 5});
  const int enter = adg.next_action(1) + 1;
  EXPECT_EQ(adg.action(enter).to, 5);
  EXPECT_EQ(adg.action(enter).handover, adg.next_action(0));
  adg.start(adg.next_action(1));
  adg.finish(adg.next_action(1));
  EXPECT_FALSE(adg.released(enter));
  adg.start(adg.next_action(0));
  adg.finish(adg.next_action(0));
  EXPECT_TRUE(adg.released(enter));
}

TEST(Adg, RotationCycleIsOneGroupThatStartsTogether)
{
  // 2x2 block 0 1 / 2 3: four agents rotate clockwise 0->1->3->2->0 in one step.
  Adg adg({0, 1, 3, 2});
  adg.append({1, 3, 2, 0});
  const int a = adg.next_action(0);
  EXPECT_EQ(adg.group_of(a).size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(adg.released(adg.next_action(i)));
  adg.start(a);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(adg.action(adg.next_action(i)).state, State::Running);
  // A later step depends on the group like on any action.
  adg.append({3, 2, 0, 1});  // rotate once more: a second group after the first
  EXPECT_FALSE(adg.released(adg.num_actions() - 1));
  for (int i = 0; i < 4; ++i) adg.finish(adg.next_action(i));
  EXPECT_EQ(drain(adg), adg.num_actions() - 4);
  EXPECT_TRUE(adg.done());
}

TEST(Adg, AMemberLeavesOnlyWhenTheWholeRotationHasArrived)
{
  // 2x3 block 0 1 4 / 2 3 5: the four agents rotate 0->1->3->2->0, then agent 0 goes on to
  // 4. A member that arrives first (a shorter move into a junction cell) must not leave:
  // the others still claim the cells of the ring (the huge AGV run's t=1695 s overlap).
  Adg adg({0, 1, 3, 2});
  adg.append({1, 3, 2, 0});
  adg.append({4, 3, 2, 0});
  const int rot = adg.next_action(0);
  const int next = adg.chain_candidate(0);
  ASSERT_GE(next, 0);
  EXPECT_EQ(adg.action(next).to, 4);
  adg.start(rot);
  EXPECT_FALSE(adg.chainable(next));  // no chaining out of a running rotation
  adg.finish(rot);
  EXPECT_EQ(adg.next_action(0), next);
  for (int i = 1; i < 4; ++i) {
    EXPECT_FALSE(adg.released(next)) << "released with " << 4 - i << " members still rotating";
    adg.finish(adg.next_action(i));
  }
  EXPECT_TRUE(adg.released(next));
  adg.start(next);
  adg.finish(next);
  EXPECT_TRUE(adg.done());
}

TEST(Adg, RejectsAConfigurationOfTheWrongSize)
{
  Adg adg({0, 1});
  EXPECT_THROW(adg.append({0}), std::invalid_argument);
}

TEST(Adg, ChainingNeedsTheHandOverNotTheOwnPreviousMove)
{
  // Line 0-1-2-3-4: agent 0 drives 0->1->2; agent 1 leaves 2 for 3 at step 0.
  Adg adg({0, 2});
  adg.append({1, 3});
  adg.append({2, 3});
  const int first = adg.next_action(0), second = adg.chain_candidate(0);
  ASSERT_GE(second, 0);
  EXPECT_EQ(adg.action(second).from, 1);
  EXPECT_FALSE(adg.chainable(second));  // its own first move is not running yet
  adg.start(first);
  EXPECT_FALSE(adg.chainable(second));  // cell 2 not handed over: agent 1 has not arrived
  EXPECT_THROW(adg.start_chained(second), std::logic_error);
  const int lead = adg.next_action(1);
  adg.start(lead);
  adg.finish(lead);
  EXPECT_TRUE(adg.chainable(second));
  adg.start_chained(second);
  adg.finish(first);
  adg.finish(second);
  EXPECT_TRUE(adg.done());
  EXPECT_EQ(adg.at(0), 2);
}

TEST(Adg, DroppingTheDonePrefixKeepsEveryDecisionAndBoundsMemory)
{
  // Ring A: 6 cells, 6 agents (every shift is a rotation group); ring B: 10 cells, 4 agents
  // moving forward at random (following). Two ADGs, one dropping its done prefix as soon as
  // 8 actions qualify, one never: the same random execution must see the same answers.
  std::mt19937 rng(7);
  planner::Config c = {0, 1, 2, 3, 4, 5, 6, 8, 11, 13};
  Adg small(c, 8), whole(c, 1 << 30);
  auto next_step = [&] {
    planner::Config n = c;
    if (rng() % 3 == 0)
      for (int i = 0; i < 6; ++i) n[i] = (c[i] + 1) % 6;
    std::vector<bool> go(10, false);
    for (int i = 6; i < 10; ++i) go[i] = rng() % 2;
    for (bool changed = true; changed;) {  // a move into a cell whose occupant stays is cancelled
      changed = false;
      for (int i = 6; i < 10; ++i) {
        const int to = 6 + (c[i] - 6 + 1) % 10;
        for (int j = 6; j < 10; ++j)
          if (go[i] && j != i && c[j] == to && !go[j]) go[i] = false, changed = true;
      }
    }
    for (int i = 6; i < 10; ++i)
      if (go[i]) n[i] = 6 + (c[i] - 6 + 1) % 10;
    c = n;
    return n;
  };
  for (int round = 0; round < 6000; ++round) {
    if (small.steps() - small.min_progress() < 3) {
      const planner::Config n = next_step();
      ASSERT_EQ(small.append(n), whole.append(n));
    }
    for (int i = 0; i < 10; ++i) {
      const int id = small.next_action(i);
      ASSERT_EQ(id, whole.next_action(i));
      ASSERT_EQ(small.progress(i), whole.progress(i));
      ASSERT_EQ(small.at(i), whole.at(i));
      ASSERT_EQ(small.chain_candidate(i), whole.chain_candidate(i));
      ASSERT_EQ(small.done(), whole.done());
      if (id < 0) continue;
      ASSERT_EQ(small.released(id), whole.released(id));
      ASSERT_EQ(small.released_following(id), whole.released_following(id));
      ASSERT_EQ(small.may_finish(id), whole.may_finish(id));
      ASSERT_EQ(small.group_of(id), whole.group_of(id));
      const int cc = small.chain_candidate(i);
      if (cc >= 0) {
        ASSERT_EQ(small.chainable_following(cc), whole.chainable_following(cc));
      }
      const uint32_t r = rng() % 4;
      if (small.action(id).state == State::Running) {
        if (r != 0 && small.may_finish(id)) {  // a rotation's members arrive one by one
          small.finish(id);
          whole.finish(id);
        }
      } else if (r != 0 && small.released_following(id)) {
        small.start_following(id);
        whole.start_following(id);
      }
    }
  }
  // Executed to the end, both are done (a one-shot run ends on it: a dropped prefix once kept
  // it false forever -- the huge warehouse ran on with every AGV on its goal).
  for (int round = 0; round < 1000 && !whole.done(); ++round)
    for (int i = 0; i < 10; ++i) {
      const int id = whole.next_action(i);
      if (id < 0) continue;
      if (whole.action(id).state == State::Running) {
        if (whole.may_finish(id)) small.finish(id), whole.finish(id);
      } else if (whole.released_following(id)) {
        small.start_following(id), whole.start_following(id);
      }
    }
  EXPECT_TRUE(whole.done());
  EXPECT_TRUE(small.done());
  EXPECT_EQ(small.num_actions(), whole.num_actions());
  EXPECT_EQ(small.actions_done(), whole.actions_done());
  EXPECT_GT(small.num_actions(), 5000);
  EXPECT_GT(small.first_action(), small.num_actions() - 200);  // dropped all but the recent
  EXPECT_LT(small.stored_actions(), 200);
  EXPECT_EQ(whole.stored_actions(), whole.num_actions());
}

// OutAndBack: u -> v -> u becomes waits on u when nobody else is on u meanwhile; not when
// someone uses u (it made way), and never in what was already handed on.
TEST(OutAndBack, CutsAStepAsideOnlyWhenNobodyUsesTheCellLeft)
{
  // Agent 0 steps 1 -> 2 and back; agent 1 stays on 5.
  executor::OutAndBack ob({1, 5}, 2);
  ob.push({2, 5});
  ob.push({2, 5});
  ob.push({1, 5});  // back: the two steps on 2 become waits on 1
  EXPECT_EQ(ob.cuts(), 1);
  ASSERT_TRUE(ob.full());
  EXPECT_EQ(ob.pop(), (planner::Config{1, 5}));
  EXPECT_EQ(ob.pop(), (planner::Config{1, 5}));
  EXPECT_EQ(ob.pop(), (planner::Config{1, 5}));
  EXPECT_TRUE(ob.empty());

  // Agent 0 makes way: 1 -> 2 while agent 1 passes 0 -> 1 -> 3, then back to 1: kept.
  executor::OutAndBack way({1, 0}, 4);
  way.push({2, 1});
  way.push({2, 3});
  way.push({1, 3});
  EXPECT_EQ(way.cuts(), 0);
  EXPECT_EQ(way.size(), 3u);
  EXPECT_FALSE(way.full());

  // Handed-on steps stay as they were (lookahead 0: nothing held).
  executor::OutAndBack late({1, 5}, 0);
  late.push({2, 5});
  EXPECT_EQ(late.pop(), (planner::Config{2, 5}));
  late.push({1, 5});
  EXPECT_EQ(late.cuts(), 0);
  EXPECT_EQ(late.pop(), (planner::Config{1, 5}));
}

// Loops (OutAndBack's `loops`): any excursion u -> ... -> u with nobody else on u meanwhile
// becomes waits on u -- here u -> v -> w -> v -> u while agent 1 passes through v (so the inner
// v -> w -> v is not cut), and once round a block u -> v -> w -> x -> u. With loops off
// neither is cut.
TEST(OutAndBack, CutsEveryExcursionBackToAFreeCellWithLoops)
{
  for (const bool loops : {true, false}) {
    // Agent 0: 1 -> 2 -> 3 -> 2 -> 1; agent 1: 7 -> 2 (while agent 0 is on 3) -> 8.
    executor::OutAndBack ob({1, 7}, 4, loops);
    ob.push({2, 7});
    ob.push({3, 2});
    ob.push({2, 8});
    ob.push({1, 8});
    EXPECT_EQ(ob.cuts(), loops ? 1 : 0) << loops;
    const std::vector<planner::Config> cut = {{1, 7}, {1, 2}, {1, 8}, {1, 8}};
    const std::vector<planner::Config> kept = {{2, 7}, {3, 2}, {2, 8}, {1, 8}};
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(ob.pop(), loops ? cut[k] : kept[k]) << loops << " " << k;

    // Round a block: 1 -> 2 -> 3 -> 4 -> 1, agent 1 stays on 9.
    executor::OutAndBack block({1, 9}, 4, loops);
    for (planner::Vertex v : {2, 3, 4, 1}) block.push({v, 9});
    EXPECT_EQ(block.cuts(), loops ? 1 : 0) << loops;
    for (planner::Vertex v : {2, 3, 4, 1}) EXPECT_EQ(block.pop()[0], loops ? 1 : v) << loops;
  }
  // Agent 1 passes u = 1 while agent 0 goes round the block: kept.
  executor::OutAndBack busy({1, 9}, 4, true);
  busy.push({2, 9});
  busy.push({3, 1});
  busy.push({4, 5});
  busy.push({1, 5});
  EXPECT_EQ(busy.cuts(), 0);
}

// Limits: a visit `keep` names (a lifelong errand's goal) is never cut, nor an excursion while
// someone else is in u's one-at-a-time zone (`exclusive`); without them both are cut.
TEST(OutAndBack, KeepsGoalVisitsAndZonesWithLimits)
{
  for (const bool limited : {true, false}) {
    executor::OutAndBackLimits goal;
    if (limited) goal.keep = [](int i, planner::Vertex v) { return i == 0 && v == 2; };  // agent 0's goal: 2
    executor::OutAndBack ob({1, 9}, 4, true, goal);
    ob.push({2, 9});
    ob.push({1, 9});
    EXPECT_EQ(ob.cuts(), limited ? 0 : 1) << limited;

    executor::OutAndBackLimits zone;  // cells 1 and 5 form one zone
    if (limited) zone.exclusive = [](planner::Vertex u, planner::Vertex w) { return (u == 1 && w == 5) || (u == 5 && w == 1); };
    executor::OutAndBack z({1, 6}, 4, true, zone);
    z.push({2, 5});  // agent 1 passes the zone while agent 0 is out of it
    z.push({1, 7});
    EXPECT_EQ(z.cuts(), limited ? 0 : 1) << limited;
  }
}
