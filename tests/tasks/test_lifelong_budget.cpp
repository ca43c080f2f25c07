// Lifelong planning time vs the budget: the goals the task layer knows are coming
// (upcoming), and prefetching their distance tables into the shared cache, which changes
// when the BFS work is done, never what is planned.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "tasks/lifelong_runner.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/task_pool.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;
using planner::Config;

TEST(Upcoming, RoundRobinAgentsHeadForTheirNextTaskAfterTheLastErrand)
{
  const auto g = ttest::grid({"......"});
  auto file = ttest::task_file(g, {{{2, 0}}, {{5, 0}}, {{0, 0}}, {{4, 0}}});
  RoundRobin rr(file);
  rr.start({0, 5});
  const auto up = rr.upcoming();
  ASSERT_EQ(up.size(), 2u);  // one-errand tasks: agent i's next is task i + 2
  EXPECT_EQ(up[0].agent, 0);
  EXPECT_EQ(up[0].goal, g.at(0, 0));
  EXPECT_EQ(up[1].agent, 1);
  EXPECT_EQ(up[1].goal, g.at(4, 0));
}

TEST(Upcoming, PoolAgentsHeadForTheNextErrandOfTheirTask)
{
  const auto g = ttest::grid({"......", "......"});
  auto file = ttest::task_file(g, {{{1, 0}, {5, 1}, {3, 1}}, {{4, 0}, {0, 1}}});
  TaskPool pool(file, g, 2, make_assigner("greedy"));
  pool.start({g.at(0, 0), g.at(5, 0)});
  auto next_of = [&](int a) {
    for (const auto& u : pool.upcoming())
      if (u.agent == a) return u.goal;
    return planner::Vertex{-1};
  };
  ASSERT_NE(pool.task_of(0), nullptr);
  ASSERT_NE(pool.task_of(1), nullptr);
  EXPECT_EQ(next_of(0), pool.task_of(0)->errands[1]);
  EXPECT_EQ(next_of(1), pool.task_of(1)->errands[1]);
  // Agent 0 completes its first errand: its next goal is the task's third errand.
  const Config at = {pool.task_of(0)->errands[0], g.at(5, 0)};
  const auto ev = pool.update(1, at);
  const Task* k = pool.task_of(0);
  ASSERT_EQ(k->next, 1);
  if (k->errands.size() == 3) EXPECT_EQ(next_of(0), k->errands[2]);
  else EXPECT_EQ(next_of(0), -1);  // last errand: the next task is not known in pool mode
}

namespace {

LifelongResult run(const ttest::Lorr& L, bool pool, bool prefetch, ActionModel model = ActionModel::Grid4)
{
  std::unique_ptr<TaskManager> tm;
  if (pool) tm = std::make_unique<TaskPool>(L.file, L.g, static_cast<int>(L.starts.size() * 3 / 2), make_assigner("greedy"));
  else tm = std::make_unique<RoundRobin>(L.file);
  LifelongOptions opt;
  opt.steps = 120;
  opt.budget = planner::Budget::expansion_count(3);  // deterministic
  opt.prefetch = prefetch;
  opt.action_model = model;
  return run_lifelong(L.g, L.starts, *tm, "rtlacam", 5, opt);
}

}  // namespace

TEST(Prefetch, ChangesWhenTablesAreGrownNotThePlan)
{
  for (const char* rel : {"/2023/random.domain/MR23-I-04.json", "/2024/random.domain/RANDOM-01.json"}) {
    const ttest::Lorr L(rel);
    const bool pool = std::string(rel).find("2024") != std::string::npos;
    for (ActionModel m : {ActionModel::Grid4, ActionModel::Rotation}) {
      const LifelongResult off = run(L, pool, false, m), on = run(L, pool, true, m);
      EXPECT_EQ(on.events, off.events) << rel;
      EXPECT_EQ(on.expansions, off.expansions) << rel;
      EXPECT_GT(on.errands_finished, 20) << rel;
      EXPECT_EQ(on.planner_errors, 0) << on.first_error;
      // The work moved: precompute ran (each step, unbounded here) and is part of planner time.
      const double pre = std::accumulate(on.precompute_ms.begin(), on.precompute_ms.end(), 0.0);
      EXPECT_GT(pre, 0) << rel;
      EXPECT_EQ(std::accumulate(off.precompute_ms.begin(), off.precompute_ms.end(), 0.0), 0) << rel;
      for (size_t k = 0; k < on.planner_ms.size(); ++k) ASSERT_LE(on.precompute_ms[k], on.planner_ms[k]);
      // One cache for planner, preference and assigner, bounded by 2 N + 256 (+ pinned).
      EXPECT_LE(on.dist_tables, 2 * L.starts.size() + 256 + L.starts.size());
      EXPECT_GT(on.dist_mb_max, 0);
    }
  }
}

TEST(Prefetch, StepsStayWithinATightTimeBudget)
{
  // A 100-agent instance at 5 ms: with the first tables grown before step 1, later ones in
  // spare time and the search stopped one expansion early, steps stay within the budget
  // (1 ms of slack for a loaded CI box; the 1,000-agent numbers are in
  // docs/rotation_lorr.md). Refinement off: an RT-LaCAM* LNS step is one indivisible
  // expansion of several ms on this map (planner/lns_refiner), not what is tested here.
#if !defined(NDEBUG) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "wall-clock budgets are measured in Release builds only";
#endif
  const ttest::Lorr L("/2023/random.domain/MR23-I-04.json");
  RoundRobin rr(L.file);
  LifelongOptions opt;
  opt.steps = 200;
  opt.budget = planner::Budget::time_ms(5);
  opt.refine = false;
  const LifelongResult r = run_lifelong(L.g, L.starts, rr, "rtlacam", 0, opt);
  EXPECT_EQ(r.planner_errors, 0) << r.first_error;
  EXPECT_GT(r.errands_finished, 300);
  const long over = std::count_if(r.planner_ms.begin(), r.planner_ms.end(), [](double ms) { return ms > 6.0; });
  EXPECT_LE(over, r.steps / 20);
  EXPECT_LT(summarize(r.planner_ms).p50, 5.0);
}
