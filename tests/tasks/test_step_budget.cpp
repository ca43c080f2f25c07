// StepBudget (tasks/step_budget.hpp) and LifelongRun's phases (tasks/lifelong_run.hpp): what a
// step may spend, and a run stepped by hand equals run_lifelong.
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
  sb.carry(3, 2.5, 7);  // the epoch start took 3 ms at the end of the last step
  EXPECT_DOUBLE_EQ(sb.left().ms, 7);
  sb.overrun.add(1);  // table growth ran 1 ms past a deadline: guard = mean + 4 dev = 1 + 4 * 0.5
  EXPECT_DOUBLE_EQ(sb.guard(), 3);
  EXPECT_DOUBLE_EQ(sb.left().ms, 4);
  sb.carry(20, 20, 0);  // never below 0
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
