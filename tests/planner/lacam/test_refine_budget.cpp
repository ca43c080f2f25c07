// RT-LaCAM* keeps the per-iteration budget while it refines (lacam.hpp, step_cost.hpp): the
// README's planner example (warehouse-10-20-10-2-1, N = 400, 1 ms, the bench's options) on
// the planning thread's CPU time. Before the refinement steps were cut to fit (main 4d7437f)
// this run measured CPU p99 2.6 ms and max 12.9 ms; after, p99 1.08 ms and max 1.10 ms.
#include <gtest/gtest.h>

#include <cstdio>

#include "planner/lacam/rt_lacam.hpp"
#include "planner/lacam/runner.hpp"
#include "planner/movingai.hpp"
#include "timing_retry.hpp"

using namespace planner;

TEST(RefineBudget, EveryIterationFitsTheCutoffOnCpuTime)
{
#if !defined(NDEBUG) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "time budgets are measured in Release builds only";
#endif
  const Graph g = load_map(RTLACAM_REPO_DATA "/movingai/warehouse-10-20-10-2-1.map");
  const Instance ins = load_scen(RTLACAM_REPO_DATA "/movingai/warehouse-10-20-10-2-1-random-1.scen", g, 400);
  LacamOptions o;  // rtlacam-bench's defaults: LaCAM* with LNS and SUO
  o.refine = true;
  o.scatter = true;
  // Tolerance as in tasks' budget tests: a loaded 2-core box adds cache misses, not preemption.
  // A CI box once charged one iteration 4.6 ms (p99 1.08) from outside: measured again then
  // (tests/common/timing_retry.hpp). The code before 4d7437f overran on every run.
  const auto within = [](const RunResult& r) {
    return r.p99_iteration_cpu_ms <= 1.5 && r.max_iteration_cpu_ms <= 3.0;
  };
  const auto run = [&] {
    RtLacam rt(g, ins.starts, ins.goals, o);
    RunOptions ro;
    ro.per_iteration = Budget::time_ms(1.0);
    ro.per_iteration.reserve_ms = 1e-6;
    ro.record_plan = false;
    const RunResult r = run_realtime(rt, g, ins.starts, ins.goals, ro);
    std::printf("iterations %lld, cpu p99 %.3f max %.3f ms, expansions %llu (%llu at the first solution)\n",
                r.iterations, r.p99_iteration_cpu_ms, r.max_iteration_cpu_ms,
                static_cast<unsigned long long>(rt.expansions()),
                static_cast<unsigned long long>(rt.lacam().expansions_at_solution()));
    EXPECT_TRUE(r.solved);
    EXPECT_EQ(r.validation_error, "");
    // It refined: most of the run's steps came after the first solution.
    EXPECT_GT(rt.expansions(), 2 * rt.lacam().expansions_at_solution());
    EXPECT_GT(rt.lacam().lns_cost().samples(), 10);
    // Refinement expansions guided by SUO's published paths were priced by their own model
    // (LacamOptions::guided_cost; off: 0 samples), and steps after an SUO slice that ran to its
    // deadline were priced cold (cold_end; off: 0).
    EXPECT_GT(rt.lacam().guided_expansion_cost().samples(), 0);
    EXPECT_GT(rt.lacam().cold_steps(), 0u);
    return r;
  };
  const RunResult r = test::first_within(3, run, within);
  EXPECT_LE(r.p99_iteration_cpu_ms, 1.5);
  EXPECT_LE(r.max_iteration_cpu_ms, 3.0);
}

// Local guidance in refinement (LacamOptions::lg_refine): a guided expansion costs a windowed
// A* per agent (several ms at N = 400); it runs only when its own learnt cost fits, else the
// expansion is unguided, so the cutoff holds. At 1 ms it never fits here; at 20 ms it does.
TEST(RefineBudget, GuidedRefinementExpansionsRunOnlyWhenTheyFit)
{
#if !defined(NDEBUG) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "time budgets are measured in Release builds only";
#endif
  const Graph g = load_map(RTLACAM_REPO_DATA "/movingai/warehouse-10-20-10-2-1.map");
  const Instance ins = load_scen(RTLACAM_REPO_DATA "/movingai/warehouse-10-20-10-2-1-random-1.scen", g, 400);
  for (double cutoff : {1.0, 20.0}) {
    const auto run = [&] {
      LacamOptions o;
      o.refine = true;
      o.scatter = true;
      o.lg_window = 5;
      o.lg_first = false;
      RtLacam rt(g, ins.starts, ins.goals, o);
      RunOptions ro;
      ro.per_iteration = Budget::time_ms(cutoff);
      ro.per_iteration.reserve_ms = 1e-6;
      ro.record_plan = false;
      ro.max_steps = cutoff > 1 ? 60 : 100000;  // the long cutoff: a few iterations are enough
      const RunResult r = run_realtime(rt, g, ins.starts, ins.goals, ro);
      std::printf("cutoff %.0f ms: iterations %lld, cpu p99 %.3f max %.3f ms, guided expansions %llu\n", cutoff,
                  r.iterations, r.p99_iteration_cpu_ms, r.max_iteration_cpu_ms,
                  static_cast<unsigned long long>(rt.lacam().guided_expansions()));
      EXPECT_EQ(r.validation_error, "");
      if (cutoff > 1) {
        EXPECT_GT(rt.lacam().guided_expansions(), 0u) << "guided expansions never fit 20 ms";
      }
      return r;
    };
    // Measured again on a miss, as above (timing_retry.hpp).
    const RunResult r = test::first_within(3, run, [&](const RunResult& x) {
      return x.p99_iteration_cpu_ms <= 1.5 * cutoff && (cutoff > 1 || x.max_iteration_cpu_ms <= 3.0);
    });
    EXPECT_LE(r.p99_iteration_cpu_ms, 1.5 * cutoff);
    if (cutoff <= 1) {
      EXPECT_LE(r.max_iteration_cpu_ms, 3.0);
    }
  }
}

// LNS's window x |V| tables are mapped ahead of the windows that use them (warm steps in the
// iterations' budgets, lazy_table.hpp) and allocated once: a step that faulted its pages in,
// or reallocated its tables as the windows grew, overran a 10 ms cutoff by up to 5 ms at
// N = 1000. Counts, not times: every LNS window ran on mapped tables.
TEST(RefineBudget, LnsStepsRunOnTablesMappedAhead)
{
  const Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  const Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 200);
  LacamOptions o;
  o.refine = true;
  RtLacam rt(g, ins.starts, ins.goals, o);
  RunOptions ro;
  ro.per_iteration = Budget::time_ms(2.0);
  ro.record_plan = false;
  ro.max_steps = 150;
  const RunResult r = run_realtime(rt, g, ins.starts, ins.goals, ro);
  EXPECT_EQ(r.validation_error, "");
  const Lacam& l = rt.lacam();
  std::printf("LNS: largest window %d, warm steps %llu, mapped for %d\n", l.lns_max_window(),
              static_cast<unsigned long long>(l.lns_warm_steps()), l.lns().warm_window());
  ASSERT_GT(l.lns_max_window(), 0) << "no LNS step ran";
  EXPECT_GT(l.lns_warm_steps(), 0u);
  EXPECT_GE(l.lns().warm_window(), l.lns_max_window());
  EXPECT_EQ(l.lns().table_allocations(), 3);
}
