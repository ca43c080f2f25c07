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

namespace {

// Strict ADG execution, one time unit per move; `late[i]` ticks before agent i may move at
// all; `switching`: try_switch on a move that waits. Returns the ticks to the end.
int run_with_late_start(Adg& adg, const std::vector<int>& late, bool switching)
{
  int t = 0;
  for (; !adg.done() && t < 100; ++t) {
    std::vector<int> run;
    for (int i = 0; i < adg.num_agents(); ++i) {
      const int id = adg.next_action(i);
      if (id < 0 || t < late[i]) continue;
      if (switching && !adg.released(id)) adg.try_switch(id);
      if (adg.released(id)) adg.start(id), run.push_back(id);
    }
    for (int id : run) adg.finish(id);
  }
  return t;
}

}  // namespace

TEST(AdgSwitch, ALateLeaderLetsTheReadyAgentPassFirst)
{
  // Agent 0 passes cell 2 at step 3 (10 -> 11 -> 12 -> 2 -> 3); agent 1 waits on 1 and
  // passes 2 after it (1 -> 2 -> 4). Agent 0 is held 5 ticks: agent 1 goes first.
  const std::vector<planner::Config> plan = {{10, 1}, {11, 1}, {12, 1}, {2, 1}, {3, 2}, {3, 4}};
  auto build = [&] {
    Adg adg(plan[0]);
    for (size_t s = 1; s < plan.size(); ++s) adg.append(plan[s]);
    return adg;
  };
  Adg fixed = build(), switched = build();
  const int t_fixed = run_with_late_start(fixed, {5, 0}, false);
  const int t_switched = run_with_late_start(switched, {5, 0}, true);
  EXPECT_EQ(t_fixed, 11);    // 5 held + 4 moves of agent 0, then agent 1's 2
  EXPECT_EQ(t_switched, 9);  // agent 1 done at 2; agent 0's 4 moves after its 5 ticks
  EXPECT_EQ(switched.switches(), 1);
  EXPECT_EQ(fixed.switches(), 0);
}

TEST(AdgSwitch, NeverSwitchesIntoACycle)
{
  // Agent 0: 20 -> 21 (w) -> 22 (v) -> 23; agent 1: 30 -> 22 (v) -> 21 (w). Passing v first,
  // agent 1 would wait on v for w, which agent 0 must leave toward v: a deadlock. Refused.
  const std::vector<planner::Config> plan = {{20, 30}, {21, 30}, {22, 30}, {23, 22}, {23, 21}};
  Adg adg(plan[0]);
  for (size_t s = 1; s < plan.size(); ++s) adg.append(plan[s]);
  const int e1 = adg.next_action(1);
  EXPECT_FALSE(adg.released(e1));
  EXPECT_FALSE(adg.try_switch(e1));  // refused by the rule already: agent 1 would park on v
  EXPECT_FALSE(adg.try_switch(e1, {1, true, false}));  // by the acyclicity check
  EXPECT_EQ(adg.switches(), 0);
  EXPECT_EQ(run_with_late_start(adg, {5, 0}, true), 10);  // plan order: 5 held + 3 moves, then agent 1's 2
  EXPECT_TRUE(adg.done());
}

TEST(AdgSwitch, RandomPlansWithLateAgentsStayValidAndEnd)
{
  // Random valid plans on a 6x6 grid (a move only into a cell free before and after),
  // appended as execution goes (a lookahead of 4 steps); random agents held; every waiting
  // move tries a switch. At every event no cell is claimed twice (claims: the cell an agent
  // stands on, and the target of its running move) and every agent moves along its own
  // plan path; every run ends (no cycle).
  long long switches = 0;
  for (int seed = 0; seed < 40; ++seed) {
    std::mt19937 rng(seed);
    const int w = 6, n = 12;
    planner::Config c(n);
    for (int i = 0; i < n; ++i) c[i] = 3 * i;  // cells 0, 3, ..., 33
    std::vector<std::vector<planner::Vertex>> path(n);
    for (int i = 0; i < n; ++i) path[i].push_back(c[i]);
    Adg adg(c);
    auto next_step = [&] {
      planner::Config nx = c;
      for (int i = 0; i < n; ++i) {
        if (rng() % 2) continue;
        const int x = c[i] % w, y = c[i] / w, d = static_cast<int>(rng() % 4);
        const int nx_x = x + (d == 0) - (d == 1), nx_y = y + (d == 2) - (d == 3);
        if (nx_x < 0 || nx_x >= w || nx_y < 0 || nx_y >= w) continue;
        const planner::Vertex to = nx_y * w + nx_x;
        if (std::find(c.begin(), c.end(), to) != c.end() || std::find(nx.begin(), nx.end(), to) != nx.end()) continue;
        nx[i] = to;
      }
      for (int i = 0; i < n; ++i)
        if (nx[i] != c[i]) path[i].push_back(nx[i]);
      c = nx;
      return nx;
    };
    std::vector<size_t> pos(n, 0);  // index into path of where the agent stands
    int steps = 0;
    for (int t = 0; t < 5000 && !(steps >= 60 && adg.done()); ++t) {
      while (steps < 60 && adg.steps() - adg.min_progress() < 10) adg.append(next_step()), ++steps;
      const int i = static_cast<int>(rng() % n);
      const int id = adg.next_action(i);
      if (id < 0 || (i % 3 == 0 && rng() % 4 != 0)) continue;  // every third agent is slow
      if (adg.action(id).state == State::Running) {
        adg.finish(id);
        ASSERT_EQ(adg.at(i), path[i][++pos[i]]);
      } else {
        // The loosest rule: the acyclicity check and the cell order alone keep it safe.
        if (!adg.released(id)) adg.try_switch(id, {1, false, false});
        if (!adg.released(id)) continue;
        adg.start(id);
      }
      std::vector<int> claims(w * w, 0);
      for (int k = 0; k < n; ++k) {
        ++claims[adg.at(k)];
        const int r = adg.next_action(k);
        if (r >= 0 && adg.action(r).state == State::Running) ++claims[adg.action(r).to];
      }
      for (int v = 0; v < w * w; ++v) ASSERT_LE(claims[v], 1) << "seed " << seed << " cell " << v << " t " << t << " switches " << adg.switches();
    }
    ASSERT_TRUE(adg.done()) << "seed " << seed;
    switches += adg.switches();
  }
  EXPECT_GT(switches, 0);
}

TEST(AdgSwitch, TheNextOccupantWaitsForTheLateAgentAfterASwitch)
{
  // Cell 2: agent 0 (late), then 1, then 2 in the plan. Agent 1 passes first; agent 2 must
  // then wait for agent 0's leave of 2, not for agent 1's.
  const std::vector<planner::Config> plan = {{10, 1, 5}, {11, 1, 5}, {12, 1, 5}, {2, 1, 5},
                                             {3, 2, 5},  {3, 4, 5},  {3, 4, 2},  {3, 4, 6}};
  Adg adg(plan[0]);
  for (size_t s = 1; s < plan.size(); ++s) adg.append(plan[s]);
  const int enter = adg.next_action(1);
  ASSERT_TRUE(adg.try_switch(enter));
  for (int k = 0; k < 2; ++k) {  // agent 1 passes cell 2
    const int id = adg.next_action(1);
    ASSERT_TRUE(adg.released(id));
    adg.start(id);
    adg.finish(id);
  }
  const int k_enter = adg.next_action(2);
  EXPECT_FALSE(adg.released(k_enter));  // agent 0 has not passed 2 yet
  EXPECT_FALSE(adg.released_following(k_enter));
  EXPECT_EQ(run_with_late_start(adg, {0, 0, 0}, true), 6);  // agent 0's 4 moves, then agent 2's 2
}
