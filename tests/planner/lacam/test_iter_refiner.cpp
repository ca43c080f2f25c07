// IterRefiner (iterative refinement, lacam3's refiner): a group never raises the copy's
// standard SOC, every window it hands out is a valid chain of configurations that splices
// into the path it was copied from, and on a congested instance it lowers the cost a lot.
// In Lacam (LacamOptions::iter_refine) its windows are adopted and the executed plan stays
// valid.
#include <gtest/gtest.h>

#include "planner/dist_table.hpp"
#include "planner/lacam/iter_refiner.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/validator.hpp"
#include "drive_refined.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

// The standard SOC of a plan (each agent up to its last arrival).
int64_t standard_soc(const std::vector<Config>& p, const Config& goals)
{
  int64_t c = 0;
  for (size_t i = 0; i < goals.size(); ++i)
    for (int t = static_cast<int>(p.size()) - 1; t >= 0; --t)
      if (p[t][i] != goals[i]) {
        c += t + 1;
        break;
      }
  return c;
}

struct Plan {
  Graph g;
  Instance ins;
  std::vector<Config> path;
};

// LaCAM's first solution (no refinement) on the first n agents of the warehouse scen.
Plan first_solution(int n)
{
  Plan p{load_map(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1.map"), {}, {}};
  p.ins = load_scen(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1-random-2-first200.scen", p.g, n);
  DistTable d(p.g);
  Lacam l(p.g, d);
  l.reset(p.ins.starts, p.ins.goals);
  EXPECT_EQ(l.search(Budget::unlimited(), true), Status::Solved);
  p.path = l.path(l.goal_node());
  return p;
}

std::vector<const Vertex*> pointers(const std::vector<Config>& path)
{
  std::vector<const Vertex*> out;
  for (const Config& c : path) out.push_back(c.data());
  return out;
}

}  // namespace

TEST(IterRefiner, GroupsNeverRaiseTheCostAndWindowsSpliceIntoAValidPlan)
{
  Plan p = first_solution(200);
  const int n = static_cast<int>(p.ins.goals.size());
  const int64_t soc0 = standard_soc(p.path, p.ins.goals);
  DistTable d(p.g);
  d.set_goals(p.ins.goals);
  IterRefiner R(p.g, d, 1);
  R.reset(pointers(p.path), n, 0, p.ins.goals, 1);
  ASSERT_EQ(R.cost(), soc0);
  // Apply every window to our own copy of the plan, as Lacam splices them.
  std::vector<Config> plan = p.path;
  int64_t last = R.cost();
  int windows = 0;
  for (int k = 0; k < 400; ++k) {
    R.step(k / 40, Clock::time_point::max());  // the frozen step moves on, as the agents do
    ASSERT_LE(R.cost(), last) << "group " << k;
    last = R.cost();
    if (k % 10 == 9) {
      RefineWindow w;
      if (!R.window(w)) continue;
      ++windows;
      ASSERT_GE(w.t0, k / 40);  // nothing before the frozen step changes
      ASSERT_EQ(w.configs.front(), plan[w.t0]);
      ASSERT_EQ(w.configs.back(), plan[w.t0 + w.configs.size() - 1]);
      for (size_t t = 0; t < w.configs.size(); ++t) plan[w.t0 + t] = w.configs[t];
      ASSERT_EQ(validate_plan(p.g, p.ins.starts, p.ins.goals, plan, true), "") << "after window " << windows;
      ASSERT_EQ(standard_soc(plan, p.ins.goals), R.cost());
      ASSERT_NE(plan[plan.size() - 2], p.ins.goals);  // the horizon stays: no repeated goal configuration
    }
  }
  EXPECT_GT(windows, 5);
  // LaCAM's first solution on 200 agents of this warehouse is congested: 400 groups cut it
  // by more than a tenth (measured: 0.55-0.6x).
  EXPECT_LT(static_cast<double>(R.cost()), 0.9 * static_cast<double>(soc0));
  std::printf("standard SOC %lld -> %lld, %d windows, %llu groups kept of %llu\n", static_cast<long long>(soc0),
              static_cast<long long>(R.cost()), windows, static_cast<unsigned long long>(R.kept()),
              static_cast<unsigned long long>(R.groups()));
}

TEST(IterRefiner, WaitsOnTheGoalBeforeTheCopyAreChargedAndANeedlessDetourGoes)
{
  // Agent 0 stood 5 steps on its goal before the copy, then steps off it and back for no
  // reason; agent 1 drives to its goal meanwhile. As BestPath prices it, agent 0 costs
  // 5 + its arrival (7), agent 1 its arrival (2). Replanned, agent 0 stays: 0 + 2.
  Graph g = test::grid({"...", "..."});
  const Config goals = test::at(g, {{0, 0}, {2, 1}});
  const std::vector<Config> plan = {test::at(g, {{0, 0}, {0, 1}}), test::at(g, {{1, 0}, {1, 1}}),
                                    test::at(g, {{0, 0}, {2, 1}})};
  ASSERT_EQ(validate_plan(g, plan[0], goals, plan, true), "");
  DistTable d(g);
  d.set_goals(goals);
  IterRefiner R(g, d, 1);
  const int32_t waits[] = {5, 0};
  R.reset(pointers(plan), 2, 0, goals, 1, waits);
  EXPECT_EQ(R.cost(), 9);
  for (int k = 0; k < 8; ++k) R.step(0, Clock::time_point::max());
  EXPECT_EQ(R.cost(), 2);
  RefineWindow w;
  ASSERT_TRUE(R.window(w));
  ASSERT_EQ(w.t0, 0);
  ASSERT_EQ(w.configs.size(), 3u);
  EXPECT_EQ(w.configs[1], test::at(g, {{0, 0}, {1, 1}}));
  EXPECT_EQ(w.agents, std::vector<int>{0});
}

TEST(IterRefiner, InTheSearchItsWindowsAreAdoptedAndTheExecutedPlanIsValid)
{
  // RT-LaCAM* with iter_refine, deterministic (a budget in expansions): windows are spliced
  // into the followed path and the executed plan is valid and reaches the goals. Without
  // iter_refine no window is spliced (the search's LNS runs instead) and this fails. The
  // executed cost against LNS is printed, not asserted: 0.95x here, but with SUO on (the
  // bench's default) 0.99-1.03x at 100-200 agents (docs/rt_lacam_star.md, session 45).
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1-random-2-first200.scen", g, 150);
  int64_t soc[2] = {0, 0};
  for (int iter = 0; iter < 2; ++iter) {
    LacamOptions o;
    o.refine = true;
    o.free_first = true;
    o.iter_refine = iter == 1;
    RtLacam rt(g, r.starts, r.goals, o);
    Validator v(g, r.starts, r.goals);
    test::drive_refined(rt, v, 3000);
    ASSERT_TRUE(rt.at_goal());
    soc[iter] = v.sum_of_costs();
    if (iter == 1) {
      EXPECT_GT(rt.lacam().iter_windows(), 0u);
      std::printf("iter_refine: %llu groups, %llu windows, %llu refused, %llu copies\n",
                  static_cast<unsigned long long>(rt.lacam().iter_groups()),
                  static_cast<unsigned long long>(rt.lacam().iter_windows()),
                  static_cast<unsigned long long>(rt.lacam().iter_refused()),
                  static_cast<unsigned long long>(rt.lacam().iter_resets()));
    }
  }
  std::printf("executed standard SOC: LNS %lld, iter_refine %lld\n", static_cast<long long>(soc[0]),
              static_cast<long long>(soc[1]));
}

TEST(IterRefiner, ARefinerThreadRunsItAndItsWindowsAreAdopted)
{
  // refine_threads = 1 with iter_refine: the worker runs the iterative refinement on its copy
  // and publishes windows; the search adopts them (as in
  // RtLacamStar.RefinerThreadWindowsAreAdoptedValidAndNeverCostlier, it waits for the worker
  // before each of the first iterations, so this does not depend on timing). Every adoption
  // keeps or lowers the followed path's standard SOC, some lower it, and the executed plan is
  // valid. Without iter_refine the worker runs LNS (refiner_iter_groups() is 0: this fails).
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1-random-2-first200.scen", g, 150);
  LacamOptions o;
  o.refine = true;
  o.iter_refine = true;
  o.refine_threads = 1;
  RtLacam rt(g, r.starts, r.goals, o);
  Validator v(g, r.starts, r.goals);
  const int steps = test::drive_refined(rt, v, 3000, 60);
  ASSERT_TRUE(rt.at_goal());
  const auto adopted = rt.lacam().thread_adoptions();
  std::printf("steps %d, windows adopted %zu (cheaper %llu), refused %llu, executed SOC %lld\n", steps, adopted.size(),
              static_cast<unsigned long long>(rt.lacam().thread_wins()),
              static_cast<unsigned long long>(rt.lacam().thread_refused()), v.sum_of_costs());
  int64_t drop = 0;
  for (const auto& [before, after] : adopted) {
    EXPECT_LE(after, before);
    drop += before - after;
  }
  std::printf("adopted windows lowered the followed path by %lld\n", static_cast<long long>(drop));
  EXPECT_GT(rt.lacam().thread_wins(), 0u);
  EXPECT_GT(rt.lacam().refiner_iter_groups(), 0u);
  EXPECT_EQ(rt.lacam().iter_groups(), 0u);  // the search made none itself
}
