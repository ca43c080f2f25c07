// PIBT as LaCAM's configuration generator: valid successors, constraints honoured.
#include <gtest/gtest.h>

#include <numeric>

#include "planner/movingai.hpp"
#include "planner/pibt.hpp"
#include "planner/priority.hpp"
#include "planner/validator.hpp"
#include "test_util.hpp"

using namespace planner;

TEST(Pibt, GeneratesValidSuccessorsOnADenseMap)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 400);
  const int n = ins.num_agents();
  for (bool swap : {false, true}) {
    DistTable d(g);
    d.set_goals(ins.goals);
    Pibt pibt(g, d, swap);
    pibt.set_goals(ins.goals);
    Rng rng(1);
    std::vector<float> prio(n), next_prio(n);
    std::vector<int32_t> order(n);
    init_priorities(ins.starts.data(), n, d, prio.data());
    initial_order(prio.data(), n, order.data());
    Config cur = ins.starts, nxt(n);
    for (int t = 0; t < 100; ++t) {
      ASSERT_TRUE(pibt.generate(cur.data(), order.data(), nullptr, nxt.data(), rng));
      ASSERT_EQ(Validator::check_transition(g, cur, nxt), "") << "t=" << t;
      cur = nxt;
      next_priorities(cur.data(), n, d, prio.data(), next_prio.data());
      prio.swap(next_prio);
      sort_by_priority(prio.data(), n, order.data());
      for (int k = 1; k < n; ++k) ASSERT_GE(prio[order[k - 1]], prio[order[k]]);
    }
  }
}

TEST(Pibt, HonoursConstraintsAndRejectsCollidingOnes)
{
  Graph g = test::grid({".....", "....."});
  Config from = test::at(g, {{0, 0}, {1, 0}, {4, 1}});
  Config goals = test::at(g, {{4, 0}, {0, 0}, {0, 1}});
  DistTable d(g);
  d.set_goals(goals);
  Pibt pibt(g, d);
  pibt.set_goals(goals);
  Rng rng(3);
  std::vector<int32_t> order = {0, 1, 2};
  Config to(3);

  // Fix agent 2 to stay and agent 0 to move down.
  Constraint root{};
  Constraint c1{&root, nullptr, 2, from[2], 1};
  Constraint c2{&c1, nullptr, 0, g.at(0, 1), 2};
  ASSERT_TRUE(pibt.generate(from.data(), order.data(), &c2, to.data(), rng));
  EXPECT_EQ(to[2], from[2]);
  EXPECT_EQ(to[0], g.at(0, 1));
  EXPECT_EQ(Validator::check_transition(g, from, to), "");

  // Two agents fixed to one vertex: rejected.
  Constraint v1{&root, nullptr, 0, g.at(0, 1), 1};
  Constraint v2{&v1, nullptr, 1, g.at(0, 1), 2};
  EXPECT_FALSE(pibt.generate(from.data(), order.data(), &v2, to.data(), rng));
  // Two agents fixed to swap: rejected.
  Constraint s1{&root, nullptr, 0, from[1], 1};
  Constraint s2{&s1, nullptr, 1, from[0], 2};
  EXPECT_FALSE(pibt.generate(from.data(), order.data(), &s2, to.data(), rng));
}
