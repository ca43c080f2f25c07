// Lifelong planning time vs the budget: the goals the task layer knows are coming
// (upcoming), and prefetching their distance tables into the shared cache, which changes
// when the BFS work is done, never what is planned.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <numeric>

#include <time.h>

#include "planner/action_preference.hpp"
#include "planner/rng.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/roundrobin.hpp"
#include "timing_retry.hpp"
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
  opt.solver.lacam.refine = false;
  const LifelongResult r = run_lifelong(L.g, L.starts, rr, "rtlacam", 0, opt);
  EXPECT_EQ(r.planner_errors, 0) << r.first_error;
  EXPECT_GT(r.errands_finished, 300);
  const long over = std::count_if(r.planner_ms.begin(), r.planner_ms.end(), [](double ms) { return ms > 6.0; });
  EXPECT_LE(over, r.steps / 20);
  EXPECT_LT(summarize(r.planner_ms).p50, 5.0);
}

namespace {

// A 200 x 200 warehouse-like grid (rows of shelves), `n` agents on random cells and
// one-errand round-robin tasks on random cells: far goals, several completions per step,
// each new goal a BFS over most of 36,000 cells.
struct Shelves {
  planner::Graph g;
  Config starts;
  std::shared_ptr<const TaskFile> file;
  explicit Shelves(int n)
  {
    const int w = 200;
    std::vector<bool> free(static_cast<size_t>(w) * w, true);
    for (int y = 0; y < w; ++y)
      for (int x = 0; x < w; ++x)
        if (y % 4 == 2 && x % 12 >= 1 && x % 12 <= 9) free[static_cast<size_t>(y) * w + x] = false;
    g = planner::Graph::from_grid(w, w, free);
    planner::Rng rng(1);
    std::vector<planner::Vertex> cells(static_cast<size_t>(g.size()));
    for (planner::Vertex v = 0; v < g.size(); ++v) cells[static_cast<size_t>(v)] = v;
    rng.shuffle(cells.data(), static_cast<int>(cells.size()));
    starts.assign(cells.begin(), cells.begin() + n);
    std::vector<std::vector<std::pair<int, int>>> lines;
    for (int k = 0; k < 20 * n; ++k) {
      const planner::Vertex v = static_cast<planner::Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      lines.push_back({{g.cell_x(v), g.cell_y(v)}});
    }
    file = ttest::task_file(g, lines);
  }
};

}  // namespace

TEST(BoundedQueries, StepsStayWithinA1msBudgetOnCpuTime)
{
  // At 1 ms with 300 agents on a 36,000-cell map, without prefetch, the search and the
  // epoch starts meet unfinished tables all the time. Queries past the step's deadline
  // answer a lower bound instead of running the BFS on the spot (dist_cache.hpp), and the
  // tables grow in the steps' spare time: the step's CPU time stays near the budget. With
  // exact queries (the code before, bound_queries = false) this run measured p99 2.2-2.4
  // ms and max 76-79 ms of CPU (step 1 grows every table; 4.8 M BFS vertices in one step).
  // CPU time, not wall time: a loaded box preempts steps without changing their work.
#if !defined(NDEBUG) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "time budgets are measured in Release builds only";
#endif
  const Shelves S(300);
  const auto run = [&] {
    RoundRobin rr(S.file);
    LifelongOptions opt;
    opt.steps = 250;
    opt.budget = planner::Budget::time_ms(1);
    opt.solver.lacam.refine = false;  // an LNS step is one indivisible expansion (planner/lns_refiner)
    // No prefetch: every new goal's table is first met by a query (set_goals' priorities,
    // PIBT), which is what is tested; prefetch only makes that rarer.
    opt.prefetch = false;
    LifelongResult r = run_lifelong(S.g, S.starts, rr, "rtlacam", 0, opt);
    const PlannerTimes cpu = summarize(r.planner_cpu_ms);
    std::printf("cpu p50 %.3f p99 %.3f max %.3f ms, query pops max %llu, estimates %llu, errands %ld\n", cpu.p50,
                cpu.p99, cpu.max, static_cast<unsigned long long>(r.query_pops_max),
                static_cast<unsigned long long>(r.dist_counters.estimates), r.errands_finished);
    return r;
  };
  // An iteration's CPU time can be inflated from outside the process: measured again on a
  // miss (tests/common/timing_retry.hpp); the exact-query code overran on every run.
  const LifelongResult r = test::first_within(3, run, [](const LifelongResult& x) {
    const PlannerTimes c = summarize(x.planner_cpu_ms);
    return c.p99 <= 1.5 && c.max <= 3.0 && x.steps_over_budget_cpu <= x.steps / 10;
  });
  EXPECT_EQ(r.planner_errors, 0) << r.first_error;
  // 464 with exact queries, 364-440 here on a quiet box; the budget is wall time, so a
  // loaded box (another suite beside it) leaves less search per step: 287 seen. Progress,
  // not a throughput figure, is what this asserts.
  EXPECT_GT(r.errands_finished, 150);
  const PlannerTimes cpu = summarize(r.planner_cpu_ms);
  EXPECT_LE(cpu.p99, 1.5);
  EXPECT_LE(cpu.max, 3.0);
  EXPECT_LE(r.steps_over_budget_cpu, r.steps / 10);
  EXPECT_GT(r.dist_counters.estimates, 0u);  // the bound was needed
}

namespace {

// A move order that costs a known CPU time per PIBT call: drawn uniformly from [lo, hi] ms
// (seeded), spent in prepare() on this thread's CPU clock, so a loaded box does not change
// it. Scores: Manhattan distance to the goal + a tie-break (no BFS tables of its own, whose
// exact queries would be outside the runner's bounded cache).
class CostlyPreference : public planner::ActionPreference {
 public:
  CostlyPreference(const planner::Graph& g, double lo, double hi) : g_(g), lo_(lo), hi_(hi), rng_(7) {}
  void set_goals(const Config& goals) override { goals_ = goals; }
  void prepare(const planner::Vertex*, int) override
  {
    const double until = cpu_ms() + lo_ + (hi_ - lo_) * rng_.uniform();
    while (cpu_ms() < until) {
    }
  }
  float score(int agent, planner::Vertex, planner::Vertex to, planner::Rng& rng) override
  {
    const planner::Vertex goal = goals_[agent];
    const int d = std::abs(g_.cell_x(to) - g_.cell_x(goal)) + std::abs(g_.cell_y(to) - g_.cell_y(goal));
    return static_cast<float>(d) + static_cast<float>(rng.uniform());
  }

 private:
  static double cpu_ms()
  {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
  }
  const planner::Graph& g_;
  Config goals_;
  double lo_, hi_;
  planner::Rng rng_;
};

}  // namespace

TEST(ExpansionCost, RotationStepsStayWithinA1msBudgetWhenExpansionsVaryInCost)
{
  // The search checks its deadline between expansions and an expansion cannot stop
  // halfway, so the runner must start one only if it fits. Here every expansion costs
  // 0.05-0.65 ms of CPU (CostlyPreference) on top of PIBT itself, under the rotation model
  // (RotationExecution window, epoch starts at the plan frontier). Stopping one *average*
  // expansion early (the runner before tasks/cost_estimate.hpp, commit 5600d8f) overran the
  // 1 ms budget whenever an expansion cost more than average: measured CPU p99 1.20-1.23
  // ms, max 1.22-1.32 ms (fails). With each expansion charged its bound (mean + 4 mean
  // deviations): p99 0.88-1.00 ms, max 0.90-1.00 ms (load average 6 on 2 cores). The p99
  // bound is what tells the two apart.
#if !defined(NDEBUG) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "time budgets are measured in Release builds only";
#endif
  const Shelves S(300);
  RoundRobin rr(S.file);
  CostlyPreference pref(S.g, 0.05, 0.65);
  LifelongOptions opt;
  opt.steps = 250;
  opt.budget = planner::Budget::time_ms(1);
  opt.action_model = ActionModel::Rotation;
  opt.solver.pref = &pref;
  opt.solver.lacam.refine = false;
  const LifelongResult r = run_lifelong(S.g, S.starts, rr, "rtlacam", 0, opt);
  EXPECT_EQ(r.planner_errors, 0) << r.first_error;
  EXPECT_GT(r.errands_finished, 50);
  const PlannerTimes cpu = summarize(r.planner_cpu_ms);
  std::printf("cpu p50 %.3f p99 %.3f max %.3f ms, expansions %llu, errands %ld\n", cpu.p50, cpu.p99, cpu.max,
              static_cast<unsigned long long>(r.expansions), r.errands_finished);
  EXPECT_LE(cpu.p99, 1.05);
  // A lone step can still run long on a busy box (the fresh-clone CI once saw max 1.47 ms
  // with p99 1.00 while another test suite ran beside it): two of 250 may pass 1.25 ms.
  const auto slow = std::count_if(r.planner_cpu_ms.begin(), r.planner_cpu_ms.end(), [](double ms) { return ms > 1.25; });
  EXPECT_LE(slow, 2);
  EXPECT_GT(r.expansions, static_cast<uint64_t>(opt.steps) / 2);  // it still searches
}
