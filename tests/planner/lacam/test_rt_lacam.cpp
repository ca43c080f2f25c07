// RT-LaCAM: the rerooted persistent search builds LaCAM's very tree, stays a tree rooted
// at the current configuration, never stalls where naive RT-LaCAM does.
#include <gtest/gtest.h>

#include "planner/lacam/lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/lacam/naive_rt_lacam.hpp"
#include "planner/lacam/pibt_planner.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/lacam/runner.hpp"
#include "planner/validator.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

struct Inst {
  std::string name;
  Graph g;
  Config s, t;
  bool swap;
};

std::vector<Inst> instances()
{
  std::vector<Inst> out;
  for (const auto& c : test::hard_cases()) {
    Graph g = test::grid(c.rows);
    Config s = test::at(g, c.starts), t = test::at(g, c.goals);
    out.push_back({c.name + "/vanilla", g, s, t, false});
    out.push_back({c.name + "/swap", g, s, t, true});
  }
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  Graph g = load_map(dir + "random-32-32-20.map");
  for (int n : {40, 120, 200}) {
    Instance ins = load_scen(dir + "random-32-32-20-random-2.scen", g, n);
    out.push_back({"random-32-32-20/" + std::to_string(n) + "/swap", g, ins.starts, ins.goals, true});
  }
  Instance ins = load_scen(dir + "random-32-32-20-random-1.scen", g, 60);
  out.push_back({"random-32-32-20/60/vanilla", g, ins.starts, ins.goals, false});
  return out;
}

// Steps RT-LaCAM with `per_step` expansions until the agents stand on their goals,
// checking the reroot invariants and validating every executed step.
void run_checked(RtLacam& rt, const Inst& in, uint64_t per_step, bool check_every_step)
{
  Validator val(in.g, in.s, in.t);
  for (long long step = 0; !rt.at_goal(); ++step) {
    ASSERT_LT(step, 200000) << "no progress";
    rt.step(Budget::expansion_count(per_step));
    rt.commit();
    ASSERT_TRUE(val.step(rt.current())) << val.error();
    const HNode* root = rt.lacam().root();
    ASSERT_EQ(Config(root->C, root->C + rt.lacam().num_agents()), rt.current()) << "root is not the current configuration";
    if (check_every_step || rt.at_goal()) {
      std::string why;
      ASSERT_TRUE(rt.lacam().check_tree(&why)) << "step " << step << ": " << why;
    }
  }
}

}  // namespace

TEST(RtLacam, BuildsTheSameTreeAsFullHorizonLacam)
{
  for (const auto& in : instances()) {
    for (uint64_t seed = 0; seed < 8; ++seed) {
      SCOPED_TRACE(in.name + " seed " + std::to_string(seed));
      LacamOptions o;
      o.swap = in.swap;
      o.seed = seed;
      DistTable d(in.g);
      Lacam full(in.g, d, o);
      full.reset(in.s, in.t);
      ASSERT_EQ(full.search(Budget::unlimited()), Status::Solved);

      for (uint64_t per_step : {1u, 7u}) {
        RtLacam rt(in.g, in.s, in.t, o);
        run_checked(rt, in, per_step, in.g.size() < 100);
        EXPECT_EQ(rt.expansions(), full.expansions()) << "per_step " << per_step;
        EXPECT_EQ(rt.explored(), full.explored()) << "per_step " << per_step;
        EXPECT_EQ(rt.current(), in.t);
      }
    }
  }
}

TEST(RtLacam, OneExpansionPerStepEvenWithAZeroBudget)
{
  const auto c = test::hard_cases().at(0);
  Graph g = test::grid(c.rows);
  RtLacam rt(g, test::at(g, c.starts), test::at(g, c.goals));
  rt.search(Budget::time_ms(0.0));
  EXPECT_EQ(rt.expansions(), 1u);
  rt.search(Budget{0.0, 0});
  EXPECT_EQ(rt.expansions(), 2u);
}

TEST(RtLacam, ReportsNoSolutionOnAnUnsolvableInstance)
{
  auto c = test::pocket_unsolvable();
  Graph g = test::grid(c.rows);
  Config s = test::at(g, c.starts), t = test::at(g, c.goals);
  RtLacam rt(g, s, t);
  RunOptions ro;
  ro.per_iteration = Budget::expansion_count(3);
  RunResult r = run_realtime(rt, g, s, t, ro);
  EXPECT_FALSE(r.solved);
  EXPECT_TRUE(r.no_solution);
  EXPECT_EQ(r.validation_error, "");
}

TEST(RtLacam, NaiveStallsWhereRtLacamSucceeds)
{
  for (const char* name : {"parked_in_corridor", "corridor_reverse3"}) {
    SCOPED_TRACE(name);
    test::Case c;
    for (auto& k : test::hard_cases())
      if (k.name == name) c = k;
    Graph g = test::grid(c.rows);
    Config s = test::at(g, c.starts), t = test::at(g, c.goals);
    for (uint64_t seed = 0; seed < 5; ++seed) {
      LacamOptions o;
      o.seed = seed;
      RunOptions ro;
      ro.per_iteration = Budget::expansion_count(1);
      ro.max_steps = 5000;
      NaiveRtLacam naive(g, s, t, o);
      RunResult rn = run_realtime(naive, g, s, t, ro);
      EXPECT_FALSE(rn.solved) << "seed " << seed;
      EXPECT_TRUE(rn.step_limit);
      EXPECT_EQ(rn.validation_error, "");
      RtLacam rt(g, s, t, o);
      RunResult rr = run_realtime(rt, g, s, t, ro);
      EXPECT_TRUE(rr.solved) << "seed " << seed;
      EXPECT_EQ(rr.validation_error, "");
      EXPECT_EQ(validate_plan(g, s, t, rr.plan, true), "");
    }
  }
}

TEST(RtLacam, WallClockBudgetRunsAreValid)
{
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  Graph g = load_map(dir + "random-32-32-20.map");
  Instance ins = load_scen(dir + "random-32-32-20-random-1.scen", g, 150);
  for (double ms : {0.01, 0.5}) {
    RtLacam rt(g, ins.starts, ins.goals);
    NaiveRtLacam naive(g, ins.starts, ins.goals);
    RunOptions ro;
    ro.per_iteration = Budget::time_ms(ms);
    ro.max_steps = 20000;
    RunResult r = run_realtime(rt, g, ins.starts, ins.goals, ro);
    EXPECT_TRUE(r.solved) << ms;
    EXPECT_EQ(validate_plan(g, ins.starts, ins.goals, r.plan, true), "");
    RunResult rn = run_realtime(naive, g, ins.starts, ins.goals, ro);
    EXPECT_EQ(rn.validation_error, "");
    EXPECT_EQ(validate_plan(g, ins.starts, ins.goals, rn.plan, rn.solved), "");
  }
}

TEST(RtLacam, NewGoalsStartANewSearchAtTheCurrentConfiguration)
{
  const auto c = test::hard_cases().at(1);  // corridor_reverse3
  Graph g = test::grid(c.rows);
  Config s = test::at(g, c.starts), t = test::at(g, c.goals);
  RtLacam rt(g, s, t);
  Validator val(g, s, t);
  for (int k = 0; k < 10000 && !rt.at_goal(); ++k) {
    rt.step(Budget::expansion_count(2));
    rt.commit();
    ASSERT_TRUE(val.step(rt.current())) << val.error();
  }
  ASSERT_TRUE(rt.at_goal());
  rt.set_goals(s);  // back to the starts
  EXPECT_EQ(rt.lacam().explored(), 1u);
  val.set_goals(s);
  for (int k = 0; k < 10000 && !rt.at_goal(); ++k) {
    rt.step(Budget::expansion_count(2));
    rt.commit();
    ASSERT_TRUE(val.step(rt.current())) << val.error();
  }
  EXPECT_EQ(rt.current(), s);
}

TEST(RtLacam, CallerGoalTestEndsTheSearch)
{
  // Lifelong-style test: "some agent reaches its goal" (goals may be shared).
  Graph g = test::grid({".....", ".....", "....."});
  Config s = test::at(g, {{0, 0}, {4, 2}}), t = test::at(g, {{4, 0}, {4, 0}});
  GoalTest some_arrived = [&](const Vertex* C) { return C[0] == t[0] || C[1] == t[1]; };
  RtLacam rt(g, s, t, LacamOptions{}, nullptr, some_arrived);
  Validator val(g, s, t);
  for (int k = 0; k < 100 && !rt.at_goal(); ++k) {
    rt.step(Budget::expansion_count(1));
    rt.commit();
    ASSERT_TRUE(val.step(rt.current())) << val.error();
  }
  ASSERT_TRUE(rt.at_goal());
  EXPECT_TRUE(rt.current()[0] == t[0] || rt.current()[1] == t[1]);
  EXPECT_LE(val.steps(), 4);  // agent 1 is two steps away, agent 0 four
}

TEST(RtLacam, CommitMovesWhereNextSaidEvenIfSearchRanInBetween)
{
  // An executor asks next(), keeps searching while the agents move, then commits.
  for (const auto& in : instances()) {
    if (in.g.size() > 100) continue;
    SCOPED_TRACE(in.name);
    LacamOptions o;
    o.swap = in.swap;
    RtLacam rt(in.g, in.s, in.t, o);
    Validator val(in.g, in.s, in.t);
    for (int k = 0; k < 100000 && !rt.at_goal(); ++k) {
      rt.search(Budget::expansion_count(1));
      const Config promised = rt.next();
      rt.search(Budget::expansion_count(3));
      rt.commit();
      ASSERT_EQ(rt.current(), promised);
      ASSERT_TRUE(val.step(rt.current())) << val.error();
      std::string why;
      ASSERT_TRUE(rt.lacam().check_tree(&why)) << why;
    }
    EXPECT_TRUE(rt.at_goal());
  }
}

TEST(RtLacam, NewEpochKeepsThePibtPriorities)
{
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  Graph g = load_map(dir + "random-32-32-20.map");
  Instance ins = load_scen(dir + "random-32-32-20-random-1.scen", g, 50);
  RtLacam rt(g, ins.starts, ins.goals);
  for (int k = 0; k < 5; ++k) {
    rt.step(Budget::expansion_count(3));
    rt.commit();
  }
  const HNode* root = rt.lacam().root();
  std::vector<float> before(root->priorities, root->priorities + 50);
  Config goals = ins.goals;
  std::swap(goals[0], goals[1]);
  rt.set_goals(goals);
  const HNode* fresh = rt.lacam().root();
  EXPECT_EQ(std::vector<float>(fresh->priorities, fresh->priorities + 50), before);
  EXPECT_EQ(rt.lacam().explored(), 1u);
}

TEST(RtLacam, NewEpochCanRestartThePriorities)
{
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  Graph g = load_map(dir + "random-32-32-20.map");
  Instance ins = load_scen(dir + "random-32-32-20-random-1.scen", g, 50);
  LacamOptions o;
  o.keep_priorities = false;
  RtLacam rt(g, ins.starts, ins.goals, o);
  for (int k = 0; k < 5; ++k) {
    rt.step(Budget::expansion_count(3));
    rt.commit();
  }
  Config goals = ins.goals;
  std::swap(goals[0], goals[1]);
  rt.set_goals(goals);
  DistTable d(g);
  d.set_goals(goals);
  const HNode* fresh = rt.lacam().root();
  for (int i = 0; i < 50; ++i) EXPECT_FLOAT_EQ(fresh->priorities[i], d.get(i, rt.current()[i]) / 50.0f);
}

// Priority hints (RealtimePlanner::set_priority_hint, priority.hpp raise_to_hint): two
// agents want the one cell between them (a shared lifelong goal). Their PIBT priorities tie
// (distance 1 / N each), so agent 0 goes first; a hint on agent 1 at the epoch start lets
// agent 1 in instead, in RT-LaCAM's first move and in PIBT's. Without the hint (or an empty
// one) agent 0 moves.
TEST(PriorityHint, AHintedAgentWinsTheContestedCellAtTheNextEpochStart)
{
  const Graph g = test::grid({"..."});
  const Config s = test::at(g, {{0, 0}, {2, 0}}), t = test::at(g, {{1, 0}, {1, 0}});
  const GoalTest someone = [&](const Vertex* C) { return C[0] == t[0] || C[1] == t[1]; };
  auto first_move = [&](RealtimePlanner& p, std::vector<float> hint) {
    p.set_priority_hint(std::move(hint));
    p.set_goals(t, someone);
    p.search(Budget::expansion_count(1));
    const Config next = p.next();
    EXPECT_EQ(validate_plan(g, s, t, {s, next}, false), "");
    return next[1] == g.at(1, 0) ? 1 : next[0] == g.at(1, 0) ? 0 : -1;
  };
  for (bool keep : {false, true}) {
    LacamOptions o;
    o.keep_priorities = keep;
    RtLacam plain(g, s, t, o, nullptr, someone);
    EXPECT_EQ(first_move(plain, {}), 0) << "keep " << keep;
    RtLacam hinted(g, s, t, o, nullptr, someone);
    EXPECT_EQ(first_move(hinted, {0.0f, 3.0f}), 1) << "keep " << keep;
    PibtPlanner pibt_plain(g, s, t, o, nullptr, someone);
    EXPECT_EQ(first_move(pibt_plain, {}), 0) << "keep " << keep;
    PibtPlanner pibt_hinted(g, s, t, o, nullptr, someone);
    EXPECT_EQ(first_move(pibt_hinted, {0.0f, 3.0f}), 1) << "keep " << keep;
  }
}
