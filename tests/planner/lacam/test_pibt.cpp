// PIBT as LaCAM's configuration generator: valid successors, constraints honoured.
#include <gtest/gtest.h>

#include <numeric>

#include "planner/movingai.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/lacam/pibt.hpp"
#include "planner/lacam/priority.hpp"
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

namespace {
// A preference that tries moves in reverse order of usefulness (farthest from the goal
// first): a stand-in for a poor learned policy.
struct Contrarian : ActionPreference {
  DistTable& d;
  int prepared = 0;
  explicit Contrarian(DistTable& dist) : d(dist) {}
  void prepare(const Vertex*, int) override { ++prepared; }
  float score(int agent, Vertex, Vertex to, Rng& rng) override
  {
    return -static_cast<float>(d.get(agent, to)) + rng.uniform();
  }
};
}  // namespace

TEST(Pibt, FollowsThePluggedPreference)
{
  Graph g = test::grid({".....", ".....", "....."});
  Config from = test::at(g, {{2, 1}}), goals = test::at(g, {{4, 1}});
  DistTable d(g);
  d.set_goals(goals);
  Contrarian pref(d);
  Pibt pibt(g, d);
  pibt.set_goals(goals);
  pibt.set_preference(&pref);
  Rng rng(0);
  std::vector<int32_t> order = {0};
  Config to(1);
  ASSERT_TRUE(pibt.generate(from.data(), order.data(), nullptr, to.data(), rng));
  EXPECT_EQ(to[0], g.at(1, 1));  // the move away from the goal
  EXPECT_EQ(pref.prepared, 1);
}

TEST(Pibt, LacamStaysCompleteUnderAnyPreference)
{
  for (const auto& c : test::hard_cases()) {
    SCOPED_TRACE(c.name);
    Graph g = test::grid(c.rows);
    Config s = test::at(g, c.starts), t = test::at(g, c.goals);
    DistTable d(g);
    Contrarian pref(d);
    Lacam lacam(g, d, LacamOptions{}, &pref);
    lacam.reset(s, t);
    ASSERT_EQ(lacam.search(Budget::unlimited()), Status::Solved);
    EXPECT_EQ(validate_plan(g, s, t, lacam.path(lacam.goal_node()), true), "");
    EXPECT_GT(pref.prepared, 0);
  }
}
