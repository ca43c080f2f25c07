// StepBudget (tasks/step_budget.hpp) and LifelongRun's phases (tasks/lifelong_run.hpp): what a
// step may spend -- in the grid's LifelongRun and in the SUMO controller's Run::step, which
// share the object -- and a run stepped by hand equals run_lifelong.
#include <gtest/gtest.h>

#include "tasks/lifelong_run.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;

TEST(StepBudget, EpochStartAndGuardComeOutOfTheStep)
{
  StepBudget sb(planner::Budget::time_ms(10), 4, 0.5, true);
  EXPECT_TRUE(sb.bounded);
  EXPECT_DOUBLE_EQ(sb.left().ms, 10);
  sb.charge(3, 2.5, 7);  // the epoch start took 3 ms at the end of the last step
  EXPECT_DOUBLE_EQ(sb.left().ms, 7);
  sb.overrun.add(1);  // table growth ran 1 ms past a deadline: guard = mean + 4 dev = 1 + 4 * 0.5
  EXPECT_DOUBLE_EQ(sb.guard(), 3);
  EXPECT_DOUBLE_EQ(sb.left().ms, 4);
  sb.paid();
  sb.charge(20, 20);  // never below 0
  EXPECT_DOUBLE_EQ(sb.left().ms, 0);
  // The epoch start may grow tables up to the precompute's share, less one first expansion.
  EXPECT_DOUBLE_EQ(sb.epoch_start_ms(), 5);
  sb.first.add(2);  // bound 2 + 4 * 1
  EXPECT_DOUBLE_EQ(sb.reserve(), 6);
  EXPECT_DOUBLE_EQ(sb.epoch_start_ms(), 0);
}

TEST(StepBudget, NoGuardWithoutABoundedTimeBudget)
{
  // Expansions only (deterministic runs), exact queries, a 0 ms budget: no query bound, no guard.
  const StepBudget cases[] = {StepBudget(planner::Budget::expansion_count(10), 4, 0.5, true),
                              StepBudget(planner::Budget::time_ms(10), 4, 0.5, false),
                              StepBudget(planner::Budget::time_ms(0), 4, 0.5, true)};
  for (StepBudget sb : cases) {
    sb.overrun.add(5);
    EXPECT_FALSE(sb.bounded);
    EXPECT_DOUBLE_EQ(sb.guard(), 0);
  }
}

// What the SUMO controller relies on and the grid did not have.

TEST(StepBudget, TheControllersCarryAddsUpOnTheCpuClock)
{
  // Between two SUMO steps' searches the controller charges several pieces of planning (the
  // tick's commits, a stuck replan, an epoch start), each in thread CPU ms: planner.budget_ms
  // bounds the planner's CPU. The step gets what all of them leave.
  StepBudget sb(planner::Budget::time_ms(1), 4, 0.5, true);
  sb.cpu_clock = true;
  sb.charge(0, 0.25);  // commits
  sb.charge(5, 0.5);   // a replan, preempted for 5 ms of wall time on a loaded machine
  EXPECT_DOUBLE_EQ(sb.carry_cpu_ms, 0.75);
  EXPECT_DOUBLE_EQ(sb.left().ms, 0.25);
  sb.paid();  // the step counted it: the next one has its whole budget
  EXPECT_DOUBLE_EQ(sb.left().ms, 1);
  // A rotation solver's search gets a tick's budget (Run::plan_budget): the carry comes out of it.
  sb.charge(0, 0.5);
  EXPECT_DOUBLE_EQ(sb.left(planner::Budget::time_ms(8)).ms, 7.5);
}

TEST(StepBudget, TheReserveLeavesTheTablesAShareOfTheStep)
{
  // After a stuck replan one expansion searches the detours too (1.2 ms where 0.3 was the
  // rule): its bound would leave the distance tables no time at all, and a search on lower
  // bounds alone stalls. Capped at 3/4 of the time left, the tables always grow by some.
  StepBudget sb(planner::Budget::time_ms(1), 4, 0.5, true);
  sb.reserve_cap = 0.75;
  EXPECT_DOUBLE_EQ(sb.tables_ms(1), 1);  // nothing learnt: the tables keep the whole step
  sb.expanded(5.0, 0);                   // no expansion: nothing to learn
  EXPECT_FALSE(sb.first.known());
  sb.expanded(0.6, 2);                   // 0.3 each: bound 0.3 + 4 x 0.15
  EXPECT_NEAR(sb.reserve(1), 0.75, 1e-12);
  EXPECT_NEAR(sb.reserve(2), 0.9, 1e-12);
  EXPECT_NEAR(sb.tables_ms(2), 1.1, 1e-12);
  sb.expanded(1.2, 1);
  EXPECT_NEAR(sb.tables_ms(1), 0.25, 1e-12);
  EXPECT_NEAR(sb.tables_ms(0.4), 0.1, 1e-12);
  // The precompute before the search: its share, less the (capped) reserve.
  EXPECT_NEAR(sb.precompute_ms(1), 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(sb.tables_ms(0), 0);  // nothing left: no deadline to move
}

TEST(StepBudget, TheControllersReserveIsTheDearestOfItsRecentSearches)
{
  // Its search is one call per SUMO step: a sample is the call's CPU over its expansions.
  // After a stuck replan the expansions that also search detours stay dear for a while: the
  // reserve holds the dearest of the last reserve_window searches, where the cost bound
  // (mean + 4 deviations) forgets it within a few cheap ones; past the window it follows
  // the cheaper ones again.
  StepBudget sb(planner::Budget::time_ms(5), 4, 0.5, true);
  sb.reserve_window = 8;
  EXPECT_DOUBLE_EQ(sb.reserve(5), 0);  // nothing learnt
  sb.expanded(0.2, 1);
  sb.expanded(1.5, 1);  // with detours
  sb.expanded(0.4, 2);  // 0.2 each
  sb.expanded(0.3, 0);  // no expansion: nothing to learn
  for (int k = 0; k < 4; ++k) sb.expanded(0.2, 1);
  EXPECT_DOUBLE_EQ(sb.reserve(5), 1.5);
  EXPECT_LT(sb.first.bound(4), 1.1);  // the cost bound has nearly forgotten it
  for (int k = 0; k < 3; ++k) sb.expanded(0.2, 1);  // 1.5 leaves the window
  EXPECT_DOUBLE_EQ(sb.reserve(5), 0.2);
  sb.reserve_cap = 0.75;  // and the cap holds: the tables always get a quarter
  sb.expanded(3, 1);
  EXPECT_DOUBLE_EQ(sb.reserve(2), 1.5);
  EXPECT_DOUBLE_EQ(sb.tables_ms(2), 0.5);
}

TEST(StepBudget, AStepTheCarryUsedUpRunsNoSearchNeverTwoInARow)
{
  // At 1000 AGVs one expansion costs more than a 1 ms step (bound 6 ms here), so no step
  // "has room for one": the grid's rule alone would never skip. A step whose carry took all
  // of its budget still runs no search -- not even the forced expansion -- and the next one
  // searches whatever its carry (max_skips 1: the search always progresses).
  StepBudget sb(planner::Budget::time_ms(1), 4, 0.5, true);
  sb.cpu_clock = true;
  sb.max_skips = 1;
  sb.first.add(2);  // bound 2 + 4 x 1
  sb.charge(0, 1.5);
  EXPECT_TRUE(sb.skip(true, 1, sb.left().ms));
  sb.paid();
  sb.charge(0, 1.5);
  EXPECT_FALSE(sb.skip(true, 1, sb.left().ms));  // never two in a row
  sb.paid();
  sb.charge(0, 2);
  EXPECT_TRUE(sb.skip(true, 1, sb.left().ms));
  EXPECT_EQ(sb.searches_skipped, 2);
  sb.paid();
  EXPECT_FALSE(sb.skip(true, 1, sb.left().ms));  // budget left: it searches
  sb.charge(0, 2);
  EXPECT_FALSE(sb.skip(false, 1, sb.left().ms));  // the back end forbids it (no time budget)
  EXPECT_EQ(sb.searches_skipped, 2);
}

TEST(StepBudget, OnlyTheGridsLateSearchSkipsAStepWithSomeTimeLeft)
{
  // 0.5 ms left, one expansion's bound 0.6 ms (budget 1 ms): the grid's --skip-late-search
  // skips it (skip_late, at most 3 in a row); the controller searches (it skips only a step
  // with nothing left: a skip costs the search a step of progress).
  StepBudget sb(planner::Budget::time_ms(1), 4, 0.5, true);
  sb.first.add(0.2);  // bound 0.2 + 4 x 0.1
  sb.charge(0.5, 0.5);
  EXPECT_FALSE(sb.skip(true, 1, sb.left().ms));
  sb.skip_late = true;
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(sb.skip(true, 1, sb.left().ms));
  EXPECT_FALSE(sb.skip(true, 1, sb.left().ms));  // max_skips 3
  EXPECT_TRUE(sb.skip(true, 1, sb.left().ms));
  EXPECT_FALSE(sb.skip(true, 0.5, sb.left().ms));  // no step has room for one: never
}

TEST(LifelongRun, SteppedByHandItIsRunLifelong)
{
  const ttest::Lorr L("/2024/random.domain/RANDOM-01.json");
  LifelongOptions opt;
  opt.steps = 60;
  opt.budget = planner::Budget{0, 20};  // expansions only: deterministic
  RoundRobin a(L.file), b(L.file);
  const LifelongResult whole = run_lifelong(L.g, L.starts, a, "rtlacam", 3, opt);
  LifelongRun run(L.g, L.starts, b, "rtlacam", 3, opt);
  long t = 0, completed = 0;
  while (!run.done()) {
    const StepRecord& rec = run.step();
    EXPECT_EQ(rec.t, ++t);
    completed += rec.completed;
  }
  const LifelongResult r = run.finish();
  EXPECT_EQ(t, 60);
  EXPECT_EQ(r.steps, 60);
  EXPECT_GT(r.errands_finished, 0);
  EXPECT_EQ(completed, r.errands_finished);
  EXPECT_EQ(r.errands_finished, whole.errands_finished);
  EXPECT_EQ(r.expansions, whole.expansions);
  ASSERT_EQ(r.events.size(), whole.events.size());
  for (size_t k = 0; k < r.events.size(); ++k) EXPECT_EQ(r.events[k].t, whole.events[k].t);
  EXPECT_EQ(r.planner_errors, 0) << r.first_error;
}
