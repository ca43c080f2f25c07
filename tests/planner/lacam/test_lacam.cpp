// LaCAM: solves what PIBT alone cannot, proves unsolvable instances unsolvable.
#include <gtest/gtest.h>

#include "planner/lacam/lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/lacam/pibt_planner.hpp"
#include "planner/lacam/runner.hpp"
#include "planner/validator.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

RunOptions one_expansion(long long max_steps)
{
  RunOptions r;
  r.per_iteration = Budget::expansion_count(1);
  r.max_steps = max_steps;
  return r;
}

}  // namespace

TEST(Lacam, SolvesWherePibtAloneFails)
{
  for (const auto& c : test::hard_cases()) {
    SCOPED_TRACE(c.name);
    Graph g = test::grid(c.rows);
    Config s = test::at(g, c.starts), t = test::at(g, c.goals);
    for (uint64_t seed = 0; seed < 5; ++seed) {
      LacamOptions o;
      o.swap = false;  // vanilla PIBT: these instances defeat it
      o.seed = seed;
      PibtPlanner pibt(g, s, t, o);
      RunResult rp = run_realtime(pibt, g, s, t, one_expansion(500));
      EXPECT_FALSE(rp.solved) << "PIBT was expected to fail (seed " << seed << ")";
      EXPECT_EQ(rp.validation_error, "");

      for (bool swap : {false, true}) {
        o.swap = swap;
        RunOptions ro;
        ro.timeout_ms = 1e9;
        RunResult r = run_full_horizon(g, s, t, o, ro);
        ASSERT_TRUE(r.solved) << "swap=" << swap << " seed=" << seed;
        EXPECT_EQ(validate_plan(g, s, t, r.plan, true), "");
        EXPECT_EQ(r.plan.front(), s);
        EXPECT_EQ(r.plan.back(), t);
      }
    }
  }
}

TEST(Lacam, ReportsNoSolutionAfterExhaustingTheSpace)
{
  auto c = test::pocket_unsolvable();
  Graph g = test::grid(c.rows);
  Config s = test::at(g, c.starts), t = test::at(g, c.goals);
  for (bool swap : {false, true}) {
    DistTable d(g);
    LacamOptions o;
    o.swap = swap;
    Lacam lacam(g, d, o);
    lacam.reset(s, t);
    EXPECT_EQ(lacam.search(Budget::unlimited()), Status::NoSolution);
    EXPECT_EQ(lacam.open_size(), 0u);
    // On a 7-vertex path 3 agents keep their order: at most 7*6*5/3! = 35 configurations.
    EXPECT_GT(lacam.explored(), 1u);
    EXPECT_LE(lacam.explored(), 35u);
    EXPECT_EQ(lacam.goal_node(), nullptr);
  }
}

TEST(Lacam, TwoAgentsSwappingOnAnEdgeIsUnsolvable)
{
  Graph g = test::grid({".."});
  DistTable d(g);
  Lacam lacam(g, d);
  lacam.reset({0, 1}, {1, 0});
  EXPECT_EQ(lacam.search(Budget::unlimited()), Status::NoSolution);
  EXPECT_EQ(lacam.explored(), 1u);
}

TEST(Lacam, StartAtGoalIsSolvedWithoutExpansion)
{
  Graph g = test::grid({"...", "..."});
  DistTable d(g);
  Lacam lacam(g, d);
  lacam.reset({0, 5}, {0, 5});
  EXPECT_EQ(lacam.search(Budget::unlimited()), Status::Solved);
  EXPECT_EQ(lacam.expansions(), 0u);
  EXPECT_EQ(lacam.path(lacam.goal_node()).size(), 1u);
}

TEST(Lacam, SolvesBenchmarkInstancesWithValidPlans)
{
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  Graph g = load_map(dir + "random-32-32-20.map");
  for (int n : {50, 150, 300}) {
    Instance ins = load_scen(dir + "random-32-32-20-random-1.scen", g, n);
    RunOptions ro;
    ro.timeout_ms = 30000;
    RunResult r = run_full_horizon(g, ins.starts, ins.goals, LacamOptions{}, ro);
    ASSERT_TRUE(r.solved) << n;
    EXPECT_EQ(validate_plan(g, ins.starts, ins.goals, r.plan, true), "");
    EXPECT_GE(r.soc, ins.soc_lower_bound(g));
  }
}
