// Monte-Carlo configuration generation (LacamOptions::mc_rollouts, lacam3's PIBT_NUM): an
// expansion keeps, of its rollouts, the successor of least edge cost + h; runs stay valid
// and complete.
#include <gtest/gtest.h>

#include "planner/lacam/lacam.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/validator.hpp"

using namespace planner;

namespace {

struct Inst {
  Graph g;
  Config s, t;
};

Inst random_32(int n)
{
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  Graph g = load_map(dir + "random-32-32-20.map");
  Instance ins = load_scen(dir + "random-32-32-20-random-1.scen", g, n);
  return {g, ins.starts, ins.goals};
}

// The successor of the root's first expansion, priced as lacam3 prices a rollout: agents not
// staying on their goals, plus the sum of distances to the goals.
int64_t first_successor_f(const Inst& in, int rollouts, uint64_t seed)
{
  LacamOptions o;
  o.seed = seed;
  o.mc_rollouts = rollouts;
  DistTable d(in.g);
  Lacam l(in.g, d, o);
  l.reset(in.s, in.t);
  l.expand();
  const HNode* h = l.top();
  EXPECT_NE(h, nullptr);
  int64_t f = 0;
  for (size_t i = 0; i < in.s.size(); ++i) {
    f += !(in.s[i] == in.t[i] && h->C[i] == in.t[i]);
    f += d.get(static_cast<int>(i), h->C[i]);
  }
  return f;
}

// The first rollout draws what the single PIBT call draws, so the kept successor is never
// worse than LaCAM's, and on a map with ties it is better for some seeds.
TEST(MonteCarlo, KeepsTheRolloutOfLeastEdgeCostPlusH)
{
  const Inst in = random_32(150);
  int better = 0;
  for (uint64_t seed = 0; seed < 12; ++seed) {
    const int64_t one = first_successor_f(in, 1, seed), many = first_successor_f(in, 8, seed);
    EXPECT_LE(many, one) << "seed " << seed;
    better += many < one;
  }
  EXPECT_GT(better, 0) << "8 rollouts never found a cheaper successor than one";
}

// Real time with Monte-Carlo generation, refinement and expansions paused at every chance:
// every move is legal and the agents arrive.
TEST(MonteCarlo, RealTimeRunsStayValidAndArrive)
{
  const Inst in = random_32(80);
  for (int where = 0; where < 3; ++where) {
    SCOPED_TRACE(where == 0 ? "everywhere" : where == 1 ? "first solution only" : "refinement only");
    LacamOptions o;
    o.pause_min_ms = 0;  // the zero budgets pause rollouts
    o.refine = true;
    o.mc_rollouts = 4;
    o.mc_first = where != 2;
    o.mc_refine = where != 1;
    RtLacam rt(in.g, in.s, in.t, o);
    Validator val(in.g, in.s, in.t);
    for (int step = 0; !rt.at_goal(); ++step) {
      ASSERT_LT(step, 5000) << "no progress";
      rt.search(step % 3 == 0 ? Budget::time_ms(0) : Budget::expansion_count(4));
      rt.next();
      rt.commit();
      ASSERT_TRUE(val.step(rt.current())) << val.error();
    }
  }
}

}  // namespace
