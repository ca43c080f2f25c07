// StepCost (step_cost.hpp): the rate a refinement step is predicted with follows a decaying
// maximum, and a step kept out because it did not fit decays it too, so it is retried.
#include <gtest/gtest.h>

#include "planner/lacam/step_cost.hpp"

using planner::StepCost;

TEST(StepCost, BelievesADearerStepAtOnceAndForgetsItSlowly)
{
  StepCost c;
  EXPECT_GT(c.units_within(1.0), 1e100);  // nothing known, no prior: anything fits
  c.record(10, 1.0);                       // 0.1 ms per unit
  EXPECT_DOUBLE_EQ(c.predict_ms(5), 0.5);
  c.record(10, 5.0);                       // a spike: 0.5 per unit, at once
  EXPECT_DOUBLE_EQ(c.rate(), 0.5);
  c.record(10, 1.0);                       // a cheap one lowers it by 5 % of the gap only
  EXPECT_NEAR(c.rate(), 0.5 - 0.05 * 0.4, 1e-12);
  EXPECT_NEAR(c.units_within(0.96), 2.0, 1e-9);
  c.set_prior(7.0);  // ignored once measured
  EXPECT_NEAR(c.rate(), 0.48, 1e-12);
}

TEST(StepCost, AStepThatNeverFitsIsRetriedAfterForgetting)
{
  StepCost c;
  c.record(1, 11.0);  // one 11 ms spike against a 1 ms room
  int skipped = 0;
  while (c.predict_ms(1) > 1.0 && skipped < 1000) {
    c.forget();
    ++skipped;
  }
  EXPECT_EQ(skipped, 47);  // 0.95^47 * 11 < 1 <= 0.95^46 * 11
}

TEST(StepCost, ForgettingBeforeTheFirstSampleScalesThePrior)
{
  // A prior that never fits must decay too, or the step is never tried and so never
  // measured (LNS at warehouse-10-20-10-2-1 N = 500, 1 ms: no step in a whole run). Callers
  // re-set the prior each time (it follows another step's rate): forget() scales them all.
  StepCost c;
  c.set_prior(1.0);
  int skipped = 0;
  while (c.predict_ms(1) > 0.1 && skipped < 1000) {
    c.forget();
    c.set_prior(1.0);  // as Lacam does before each try
    ++skipped;
  }
  EXPECT_LT(skipped, 100);  // 0.95^45 < 0.1
  EXPECT_LE(c.predict_ms(1), 0.1);
  c.record(1, 0.5);  // measured: the prior no longer counts
  c.set_prior(1.0);
  EXPECT_DOUBLE_EQ(c.rate(), 0.5);
}
