// LnsRefiner: a step never makes a path costlier, keeps it valid, and removes a needless
// detour/wait when the neighbourhood contains the delayed agent.
#include <gtest/gtest.h>

#include "planner/dist_table.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/lacam/lns_refiner.hpp"
#include "planner/movingai.hpp"
#include "planner/validator.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

int64_t cost(const std::vector<Config>& p, const Config& goals)
{
  int64_t c = 0;
  for (int i = 0; i < static_cast<int>(goals.size()); ++i) c += LnsRefiner::agent_cost(p, goals, i, 0, static_cast<int>(p.size()) - 1);
  return c;
}

}  // namespace

TEST(LnsRefiner, RemovesANeedlessWait)
{
  Graph g = test::grid({".....", "....."});
  const Config s = test::at(g, {{0, 0}, {0, 1}}), t = test::at(g, {{4, 0}, {4, 1}});
  // Agent 0 waits three steps before going; agent 1 goes at once.
  std::vector<Config> p;
  const int x0[] = {0, 0, 0, 0, 1, 2, 3, 4}, x1[] = {0, 1, 2, 3, 4, 4, 4, 4};
  for (int k = 0; k < 8; ++k) p.push_back(test::at(g, {{x0[k], 0}, {x1[k], 1}}));
  ASSERT_EQ(validate_plan(g, s, t, p, true), "");
  DistTable d(g);
  d.set_goals(t);
  LnsRefiner lns(g, d);
  Rng rng(3);
  const int64_t before = cost(p, t);
  bool improved = false;
  for (int k = 0; k < 20 && !improved; ++k) improved = lns.step(p, t, 2, rng);
  EXPECT_TRUE(improved);
  EXPECT_EQ(validate_plan(g, s, t, p, true), "");
  EXPECT_EQ(cost(p, t), 8);  // both agents go straight: 4 + 4
  EXPECT_LT(cost(p, t), before);
}

TEST(LnsRefiner, StepsKeepPathsValidAndNeverCostlier)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 80);
  DistTable d(g);
  LacamOptions o;
  Lacam l(g, d, o);
  l.reset(ins.starts, ins.goals);
  ASSERT_EQ(l.search(Budget::unlimited()), Status::Solved);
  std::vector<Config> p = l.path(l.goal_node());
  for (auto [window, nbh] : {std::pair{8, LnsNeighbourhood::random}, std::pair{256, LnsNeighbourhood::random},
                             std::pair{256, LnsNeighbourhood::blocking}, std::pair{64, LnsNeighbourhood::intersection},
                             std::pair{256, LnsNeighbourhood::adaptive}}) {
    LnsRefiner lns(g, d, window, nbh);
    Rng rng(window + static_cast<int>(nbh));
    int64_t last = cost(p, ins.goals);
    for (int k = 0; k < 200; ++k) {
      const bool better = lns.step(p, ins.goals, 8, rng);
      const int64_t c = cost(p, ins.goals);
      if (better) {
        EXPECT_LT(c, last);
      } else {
        EXPECT_EQ(c, last);
      }
      last = c;
    }
    EXPECT_EQ(validate_plan(g, ins.starts, ins.goals, p, true), "");
  }
}

// Agent 0 waits behind agent 1, who waits needlessly in a one-cell lane (three agents
// are parked on their goals in dead-end alcoves below it). Replanning agent 0 alone cannot help; the blocking
// neighbourhood puts its blocker in the set, so every first step improves, whichever of the
// two delayed agents seeds it.
TEST(LnsRefiner, BlockingNeighbourhoodReplansTheBlocker)
{
  Graph g = test::grid({"........", "@.@.@.@@"});
  const std::vector<std::pair<int, int>> parked{{1, 1}, {3, 1}, {5, 1}};
  auto config = [&](int x0, int x1) {
    std::vector<std::pair<int, int>> c{{x0, 0}, {x1, 0}};
    c.insert(c.end(), parked.begin(), parked.end());
    return test::at(g, c);
  };
  const int x0[] = {0, 0, 0, 0, 1, 2, 3, 4, 4}, x1[] = {1, 1, 1, 1, 2, 3, 4, 5, 5};
  std::vector<Config> p0;
  for (int t = 0; t < 9; ++t) p0.push_back(config(x0[t], x1[t]));
  const Config s = p0.front(), t = config(4, 5);
  ASSERT_EQ(validate_plan(g, s, t, p0, true), "");
  DistTable d(g);
  d.set_goals(t);
  const int64_t before = cost(p0, t);  // 7 + 7
  int random_wins = 0;
  for (uint64_t seed = 0; seed < 20; ++seed) {
    for (auto nbh : {LnsNeighbourhood::blocking, LnsNeighbourhood::random}) {
      std::vector<Config> p = p0;
      LnsRefiner lns(g, d, 256, nbh);
      Rng rng(seed);
      const bool won = lns.step(p, t, 2, rng);
      EXPECT_EQ(validate_plan(g, s, t, p, true), "");
      if (nbh == LnsNeighbourhood::blocking) {
        EXPECT_TRUE(won) << "seed " << seed;
        EXPECT_EQ(lns.last_heuristic(), 1);
        EXPECT_LT(cost(p, t), before);
      } else {
        random_wins += won;
      }
    }
  }
  EXPECT_LT(random_wins, 20);  // the instance needs the blocker: random sets miss it
}

TEST(LnsRefiner, UnknownNeighbourhoodNameIsAnError)
{
  EXPECT_EQ(parse_lns_neighbourhood("blocking"), LnsNeighbourhood::blocking);
  EXPECT_THROW(parse_lns_neighbourhood("ring"), std::invalid_argument);
}

// The window x |V| tables are allocated once, for the largest window, however the windows
// of the steps grow (a table that grew with them was freed and faulted in anew at each
// growth: 9-15 ms steps at N = 1000), and warm() maps them ahead: up to the window asked
// for, in pieces that stop at the deadline, and the steps then give the same paths as
// without warming.
TEST(LnsRefiner, TablesAreAllocatedOnceAndWarmedAhead)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 80);
  DistTable d(g);
  Lacam l(g, d);
  l.reset(ins.starts, ins.goals);
  ASSERT_EQ(l.search(Budget::unlimited()), Status::Solved);
  const std::vector<Config> p0 = l.path(l.goal_node());
  std::vector<Config> cold = p0, warm = p0;
  LnsRefiner a(g, d, 256), b(g, d, 256);
  Rng ra(5), rb(5);
  EXPECT_EQ(b.warm_window(), -1);
  // A passed deadline: one piece (16 pages a table) per call, not the whole window.
  ASSERT_FALSE(b.warm(256, Clock::time_point::min()));
  const int piece = b.warm_window();
  EXPECT_LT(piece, 64);
  for (int w : {4, 8, 16, 32, 64}) {
    a.set_window(w);
    b.set_window(w);
    ASSERT_TRUE(b.warm(w, Clock::time_point::max()));
    EXPECT_GE(b.warm_window(), w);
    for (int k = 0; k < 10; ++k) {
      a.step(cold, ins.goals, 8, ra);
      b.step(warm, ins.goals, 8, rb);
    }
  }
  EXPECT_EQ(cold, warm);
  EXPECT_EQ(a.table_allocations(), 3);
  EXPECT_EQ(b.table_allocations(), 3);
  EXPECT_EQ(validate_plan(g, ins.starts, ins.goals, warm, true), "");
}

// Stop cost (issue 21): agent 0 follows agent 1, who creeps along a corridor (wait, move,
// wait, move), and copies its stop-and-go: two moves from rest. Waiting first and then driving
// on costs the same (loss and standard SOC) with one move from rest. Only a stop cost makes a
// step prefer it; without one the step finds nothing better and the path keeps both stops.
TEST(LnsRefiner, StopCostMergesStopAndGoIntoOneStop)
{
  Graph g = test::grid({"......"});
  const Config s = test::at(g, {{0, 0}, {2, 0}}), t = test::at(g, {{4, 0}, {5, 0}});
  const int x0[] = {0, 1, 1, 2, 2, 3, 4}, x1[] = {2, 2, 3, 3, 4, 4, 5};
  for (Objective obj : {Objective::loss, Objective::soc})
    for (int c : {0, 1}) {
      std::vector<Config> p;
      for (int k = 0; k < 7; ++k) p.push_back(test::at(g, {{x0[k], 0}, {x1[k], 0}}));
      ASSERT_EQ(validate_plan(g, s, t, p, true), "");
      ASSERT_EQ(LnsRefiner::agent_stops(p, 0, 0, 6), 2);
      DistTable d(g);
      d.set_goals(t);
      LnsRefiner lns(g, d, 32, LnsNeighbourhood::random, obj);
      lns.set_stop_cost(c);
      Rng rng(5);
      bool improved = false;
      for (int k = 0; k < 10; ++k) improved |= lns.step(p, t, 1, rng, Clock::time_point::max(), nullptr, 0);
      EXPECT_EQ(validate_plan(g, s, t, p, true), "");
      EXPECT_EQ(improved, c > 0) << "objective " << static_cast<int>(obj) << " stop cost " << c;
      EXPECT_EQ(LnsRefiner::agent_stops(p, 0, 0, 6), c > 0 ? 1 : 2);
      EXPECT_EQ(cost(p, t), 6 + 6);  // neither's loss changes
      EXPECT_EQ(p[6][0], t[0]);
    }
}

// Moves tie-break (issue 21): agent 0 detours around agent 1, who leaves the corridor cell
// (1, 0) at step 3, and arrives at step 4; waiting two steps and going straight arrives at
// step 4 too (same standard SOC, same loss) with 2 moves instead of 4. Only counting moves
// instead of the loss makes a step prefer the wait (a physical executor spends time on
// moves, not on planned waits); with the loss the step finds nothing better.
TEST(LnsRefiner, CountMovesPrefersWaitingToDetouring)
{
  Graph g = test::grid({"...", "..."});
  const Config s = test::at(g, {{0, 0}, {1, 0}}), t = test::at(g, {{2, 0}, {1, 1}});
  const int x0[] = {0, 0, 1, 2, 2, 2}, y0[] = {0, 1, 1, 1, 0, 0}, y1[] = {0, 0, 0, 1, 1, 1};
  for (bool moves : {false, true}) {
    std::vector<Config> p;
    for (int k = 0; k < 6; ++k) p.push_back(test::at(g, {{x0[k], y0[k]}, {1, y1[k]}}));
    ASSERT_EQ(validate_plan(g, s, t, p, true), "");
    ASSERT_EQ(LnsRefiner::agent_moves(p, 0, 0, 5), 4);
    DistTable d(g);
    d.set_goals(t);
    LnsRefiner lns(g, d, 32, LnsNeighbourhood::random, Objective::soc);
    lns.set_count_moves(moves);
    Rng rng(5);
    bool improved = false;
    for (int k = 0; k < 10; ++k) improved |= lns.step(p, t, 1, rng, Clock::time_point::max(), nullptr, 0);
    EXPECT_EQ(validate_plan(g, s, t, p, true), "");
    EXPECT_EQ(improved, moves);
    EXPECT_EQ(LnsRefiner::agent_moves(p, 0, 0, 5), moves ? 2 : 4);
    EXPECT_EQ(LnsRefiner::agent_soc(p, t, 0, 0, 5, true), 4);  // arrives at step 4 either way
  }
}
