// LnsRefiner: a step never makes a path costlier, keeps it valid, and removes a needless
// detour/wait when the neighbourhood contains the delayed agent.
#include <gtest/gtest.h>

#include "planner/dist_table.hpp"
#include "planner/lacam.hpp"
#include "planner/lns_refiner.hpp"
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
  for (int window : {8, 256}) {
    LnsRefiner lns(g, d, window);
    Rng rng(window);
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
