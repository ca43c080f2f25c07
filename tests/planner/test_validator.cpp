// The validator catches every kind of invalid step and accounts the paper's cost.
#include <gtest/gtest.h>

#include "planner/validator.hpp"
#include "test_util.hpp"

using namespace planner;

class ValidatorTest : public testing::Test {
 protected:
  Graph g = test::grid({"...", ".@.", "..."});
  Vertex a = g.at(0, 0), b = g.at(1, 0), c = g.at(2, 0), d = g.at(0, 1);
};

TEST_F(ValidatorTest, AcceptsWaitsAndMoves)
{
  EXPECT_EQ(Validator::check_transition(g, {a, c}, {b, c}), "");
  EXPECT_EQ(Validator::check_transition(g, {a, b}, {d, a}), "");  // following is allowed
  EXPECT_EQ(Validator::check_transition(g, {a, c}, {a, c}), "");
}

TEST_F(ValidatorTest, RejectsVertexConflicts)
{
  auto e = Validator::check_transition(g, {a, c}, {b, b});
  EXPECT_NE(e.find("vertex conflict"), std::string::npos) << e;
}

TEST_F(ValidatorTest, RejectsSwapConflicts)
{
  auto e = Validator::check_transition(g, {a, b}, {b, a});
  EXPECT_NE(e.find("swap conflict"), std::string::npos) << e;
}

TEST_F(ValidatorTest, RejectsJumps)
{
  auto e = Validator::check_transition(g, {a}, {c});
  EXPECT_NE(e.find("not adjacent"), std::string::npos) << e;
  e = Validator::check_transition(g, {a}, {99});
  EXPECT_NE(e.find("not in the graph"), std::string::npos) << e;
  e = Validator::check_transition(g, {a, b}, {a});
  EXPECT_NE(e.find("agents"), std::string::npos) << e;
}

TEST_F(ValidatorTest, WholePlansAndCost)
{
  Config s = {a, c}, t = {b, d};
  // agent 0: a -> b, then stays on its goal (free); agent 1: c -> b? no: c -> ... -> d
  std::vector<Config> plan = {{a, c}, {b, c}, {b, c}};
  EXPECT_NE(validate_plan(g, s, t, plan, true).find("not the goals"), std::string::npos);
  EXPECT_EQ(validate_plan(g, s, t, plan, false), "");
  EXPECT_NE(validate_plan(g, {b, c}, t, plan, false).find("timestep 0"), std::string::npos);
  EXPECT_NE(validate_plan(g, {a, a}, t, {{a, a}}, false).find("vertex conflict"), std::string::npos);

  Validator v(g, {a, b}, {b, b});  // goals need not be distinct for cost accounting
  EXPECT_EQ(v.sum_of_costs(), 0);  // no step yet
  ASSERT_TRUE(v.step({d, a}));     // both move: loss 2
  ASSERT_TRUE(v.step({d, b}));     // agent 1 moves onto its goal: 1 + agent 0 waits off-goal: 1
  ASSERT_TRUE(v.step({d, b}));     // agent 1 stays on goal: free; agent 0 waits: 1
  EXPECT_EQ(v.sum_of_loss(), 5);
  // Standard: agent 1 last arrives at step 2 (cost 2); agent 0 is still off its goal after
  // 3 steps (cost 3, the steps so far).
  EXPECT_EQ(v.sum_of_costs(), 5);
  ASSERT_TRUE(v.step({d, b}));
  EXPECT_EQ(v.sum_of_costs(), 6);
  EXPECT_EQ(v.sum_of_loss(), 6);
  EXPECT_EQ(v.steps(), 4);
  EXPECT_FALSE(v.step({b, b}));
  EXPECT_FALSE(v.ok());
  EXPECT_NE(v.error().find("step 4 -> 5"), std::string::npos) << v.error();
}

TEST_F(ValidatorTest, StandardCostChargesAgentsThatParkOnTheirGoalAndLeaveAgain)
{
  // Agent 0 reaches its goal b at step 1, parks there for two steps, steps off to make room
  // at step 4 and is back at step 5: standard cost 5 (last arrival), loss 3 (the two parked
  // steps are free). Agent 1 starts on its goal d and never leaves: 0 either way.
  Validator v(g, {a, d}, {b, d});
  for (const Config& c : std::vector<Config>{{b, d}, {b, d}, {b, d}, {c, d}, {b, d}, {b, d}})
    ASSERT_TRUE(v.step(c)) << v.error();
  EXPECT_EQ(v.sum_of_costs(), 5);
  EXPECT_EQ(v.sum_of_loss(), 3);
  // Never leaving: both count the same (one move, then free waits).
  Validator w(g, {a, d}, {b, d});
  for (const Config& c : std::vector<Config>{{b, d}, {b, d}, {b, d}}) ASSERT_TRUE(w.step(c));
  EXPECT_EQ(w.sum_of_costs(), 1);
  EXPECT_EQ(w.sum_of_loss(), 1);
}
