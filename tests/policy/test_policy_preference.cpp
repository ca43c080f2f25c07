// PolicyPreference: the CS-PIBT move order, and the policy inside LaCAM / RT-LaCAM /
// PIBT keeps every run valid and the complete planners complete.
#include <gtest/gtest.h>

#include "planner/lacam/lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/lacam/naive_rt_lacam.hpp"
#include "planner/lacam/pibt_planner.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/lacam/runner.hpp"
#include "planner/validator.hpp"
#include "policy/actions.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"
#include "test_util.hpp"

using namespace planner;
using namespace policy;

namespace {

const Model& trained()
{
  static const Model m = load_weights(RTLACAM_POLICY_MODELS "/random-32-32-20.bin");
  return m;
}

// A model that ignores its input: logits = bias. Radius 1.
Model constant_model(std::initializer_list<float> logits)
{
  Model m;
  m.spec.radius = 1;
  Dense d;
  d.w = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>::Zero(kNumActions, m.spec.size());
  d.b.resize(kNumActions);
  int k = 0;
  for (float l : logits) d.b[k++] = l;
  m.layers = {d};
  return m;
}

}  // namespace

TEST(Actions, GridMoves)
{
  Graph g = test::grid({"...", "...", "..."});
  const Vertex c = g.at(1, 1);
  EXPECT_EQ(action_of(g, c, c), kStay);
  EXPECT_EQ(action_of(g, c, g.at(1, 0)), kUp);
  EXPECT_EQ(action_of(g, c, g.at(1, 2)), kDown);
  EXPECT_EQ(action_of(g, c, g.at(0, 1)), kLeft);
  EXPECT_EQ(action_of(g, c, g.at(2, 1)), kRight);
  EXPECT_EQ(action_of(g, c, g.at(2, 2)), -1);
  EXPECT_STREQ(action_name(kLeft), "left");
}

TEST(PolicyPreference, OrdersMovesByProbability)
{
  Graph g = test::grid({"...", "...", "..."});
  const Model m = constant_model({0, 3, 1, 2, -1});  // up > left > down > stay > right
  const Config goals = test::at(g, {{0, 0}});
  PolicyPreference pref(g, m, goals);
  const Config c = test::at(g, {{1, 1}});
  pref.prepare(c.data(), 1);
  EXPECT_NEAR(pref.probabilities().col(0).sum(), 1.0f, 1e-6f);
  EXPECT_GT(pref.probabilities()(kUp, 0), pref.probabilities()(kLeft, 0));
  Rng rng(0);
  const Vertex v = c[0];
  const float up = pref.score(0, v, g.at(1, 0), rng), left = pref.score(0, v, g.at(0, 1), rng),
              down = pref.score(0, v, g.at(1, 2), rng), stay = pref.score(0, v, v, rng),
              right = pref.score(0, v, g.at(2, 1), rng);
  EXPECT_LT(up, left);
  EXPECT_LT(left, down);
  EXPECT_LT(down, stay);
  EXPECT_LT(stay, right);
  EXPECT_EQ(pref.inferences(), 1);
  pref.prepare(c.data(), 1);  // same configuration: served from the last result
  EXPECT_EQ(pref.inferences(), 1);
}

// PIBT follows the policy; a preferred move into a wall is not a candidate (CS-PIBT drops
// invalid actions), so the next best is taken; a collision is never.
TEST(PolicyPreference, PibtFollowsThePolicyBehindItsShield)
{
  Graph g = test::grid({".@.", "...", "..."});
  const Model m = constant_model({0, 5, 1, 3, -1});  // up > left > down > stay > right
  const Config goals = test::at(g, {{2, 2}, {0, 0}});
  PolicyPreference pref(g, m, goals);
  DistTable d(g);
  d.set_goals(goals);
  Pibt pibt(g, d, /*swap=*/false);
  pibt.set_goals(goals);
  pibt.set_preference(&pref);
  Rng rng(0);
  // Agent 0 at (1,1): up is a wall -> left is taken. Agent 1 at (2,0): up is off the map,
  // left is a wall -> down.
  Config from = test::at(g, {{1, 1}, {2, 0}}), to(2);
  std::vector<int32_t> order = {0, 1};
  ASSERT_TRUE(pibt.generate(from.data(), order.data(), nullptr, to.data(), rng));
  EXPECT_EQ(to, test::at(g, {{0, 1}, {2, 1}}));
  // Agent 0 at (0,1) wants up, where agent 1 is; agent 1's own moves are a wall, off the map
  // or the swap with agent 0: whatever PIBT picks, the shield keeps it valid.
  from = test::at(g, {{0, 1}, {0, 0}});
  ASSERT_TRUE(pibt.generate(from.data(), order.data(), nullptr, to.data(), rng));
  EXPECT_EQ(Validator::check_transition(g, from, to), "");
}

TEST(PolicyPreference, LacamWithThePolicySolvesTheHardCases)
{
  for (const auto& c : test::hard_cases()) {
    SCOPED_TRACE(c.name);
    Graph g = test::grid(c.rows);
    const Config s = test::at(g, c.starts), t = test::at(g, c.goals);
    PolicyPreference pref(g, trained(), t);
    DistTable d(g);
    Lacam lacam(g, d, LacamOptions{}, &pref);
    lacam.reset(s, t);
    ASSERT_EQ(lacam.search(Budget::unlimited()), Status::Solved);
    EXPECT_EQ(validate_plan(g, s, t, lacam.path(lacam.goal_node()), true), "");
    EXPECT_GT(pref.inferences(), 0);

    RunOptions ro;
    ro.per_iteration = Budget::expansion_count(1);
    const RunResult r = run_full_horizon(g, s, t, LacamOptions{}, ro, &pref);
    EXPECT_TRUE(r.solved);
    EXPECT_EQ(r.validation_error, "");
  }
}

TEST(PolicyPreference, RtLacamWithThePolicySolvesTheHardCases)
{
  for (uint64_t budget : {1, 3, 50}) {
    for (const auto& c : test::hard_cases()) {
      SCOPED_TRACE(c.name + " budget " + std::to_string(budget));
      Graph g = test::grid(c.rows);
      const Config s = test::at(g, c.starts), t = test::at(g, c.goals);
      PolicyPreference pref(g, trained(), t);
      RtLacam p(g, s, t, LacamOptions{}, &pref);
      RunOptions ro;
      ro.per_iteration = Budget::expansion_count(budget);
      ro.max_steps = 20000;
      const RunResult r = run_realtime(p, g, s, t, ro);
      EXPECT_TRUE(r.solved);
      EXPECT_EQ(r.validation_error, "");
    }
  }
}

TEST(PolicyPreference, UnsolvableStaysProvenUnsolvable)
{
  const auto c = test::pocket_unsolvable();
  Graph g = test::grid(c.rows);
  const Config s = test::at(g, c.starts), t = test::at(g, c.goals);
  PolicyPreference pref(g, trained(), t);
  DistTable d(g);
  Lacam lacam(g, d, LacamOptions{}, &pref);
  lacam.reset(s, t);
  EXPECT_EQ(lacam.search(Budget::unlimited()), Status::NoSolution);
}

// On a real map: CS-PIBT (no search) and the policy inside RT-LaCAM and naive RT-LaCAM
// produce valid runs; RT-LaCAM solves it.
TEST(PolicyPreference, ValidRunsOnRandom32)
{
  const Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  const Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 100);
  RunOptions ro;
  ro.per_iteration = Budget::expansion_count(5);
  ro.max_steps = 2000;
  for (const std::string solver : {"cspibt", "rtlacam", "naive"}) {
    SCOPED_TRACE(solver);
    PolicyPreference pref(g, trained(), ins.goals);
    std::unique_ptr<RealtimePlanner> p;
    if (solver == "cspibt") p = std::make_unique<PibtPlanner>(g, ins.starts, ins.goals, LacamOptions{}, &pref);
    else if (solver == "rtlacam") p = std::make_unique<RtLacam>(g, ins.starts, ins.goals, LacamOptions{}, &pref);
    else p = std::make_unique<NaiveRtLacam>(g, ins.starts, ins.goals, LacamOptions{}, &pref);
    const RunResult r = run_realtime(*p, g, ins.starts, ins.goals, ro);
    EXPECT_EQ(r.validation_error, "");
    if (solver == "rtlacam") {
      EXPECT_TRUE(r.solved);
    }
    EXPECT_GT(pref.inferences(), 0);
  }
}

TEST(PolicyPreference, RejectsMismatchedModels)
{
  Graph g = test::grid({"..."});
  Model m = constant_model({0, 0, 0, 0, 0});
  m.spec.radius = 2;  // the layer still takes radius-1 inputs
  EXPECT_THROW(PolicyPreference(g, m, test::at(g, {{0, 0}})), std::invalid_argument);
}
