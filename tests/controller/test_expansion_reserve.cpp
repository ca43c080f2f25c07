// ExpansionReserve (controller/expansion_reserve.hpp): the share of a step's budget that
// table and detour growth leave to the expansion that queries them.
#include <gtest/gtest.h>

#include "controller/expansion_reserve.hpp"

using controller::ExpansionReserve;

TEST(ExpansionReserve, IsTheDearestRecentExpansionCappedAtAShareOfTheBudget)
{
  ExpansionReserve r(4, 0.75);
  EXPECT_EQ(r.ms(1.0), 0);  // nothing learnt: the tables keep the whole budget
  r.record(0.3, 1);         // a plain one
  r.record(0.9, 2);         // 0.45 each
  r.record(5.0, 0);         // no expansion: nothing to learn
  EXPECT_DOUBLE_EQ(r.ms(1.0), 0.45);
  r.record(1.2, 1);                  // one that also grew detours
  EXPECT_DOUBLE_EQ(r.ms(1.0), 0.75);  // capped: the tables always get a quarter
  EXPECT_DOUBLE_EQ(r.ms(2.0), 1.2);
  EXPECT_EQ(r.ms(0.0), 0);            // no budget left: no deadline to move
}

TEST(ExpansionReserve, ForgetsExpansionsOlderThanItsWindow)
{
  // Once the detours are searched the expansions are cheaper again: the reserve follows
  // the last window's, not the dearest ever.
  ExpansionReserve r(3, 1.0);
  r.record(1.5, 1);
  for (int k = 0; k < 3; ++k) r.record(0.4, 1);
  EXPECT_DOUBLE_EQ(r.ms(5.0), 0.4);
  r.record(0.9, 1);
  EXPECT_DOUBLE_EQ(r.ms(5.0), 0.9);
}
