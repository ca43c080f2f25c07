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
  ASSERT_TRUE(v.step({d, a}));     // both move: cost 2
  ASSERT_TRUE(v.step({d, b}));     // agent 1 moves onto its goal: 1 + agent 0 waits off-goal: 1
  ASSERT_TRUE(v.step({d, b}));     // agent 1 stays on goal: free; agent 0 waits: 1
  EXPECT_EQ(v.sum_of_costs(), 5);
  EXPECT_EQ(v.steps(), 3);
  EXPECT_FALSE(v.step({b, b}));
  EXPECT_FALSE(v.ok());
  EXPECT_NE(v.error().find("step 3 -> 4"), std::string::npos) << v.error();
}
