// ExpansionReserve (controller/expansion_reserve.hpp): the share of a step's budget that
// table and detour growth leave to the expansion that queries them.
#include <gtest/gtest.h>

#include "controller/expansion_reserve.hpp"

using controller::ExpansionReserve;

TEST(ExpansionReserve, IsTheCheapestRecentExpansionCappedAtAShareOfTheBudget)
{
  ExpansionReserve r(4, 0.75);
  EXPECT_EQ(r.ms(1.0), 0);  // nothing learnt: the tables keep the whole budget
  r.record(1.8, 1);         // an expansion that also grew detours
  r.record(0.7, 1);         // a plain one
  r.record(2.0, 2);         // 1.0 each
  r.record(0.5, 0);         // no expansion: nothing to learn
  EXPECT_DOUBLE_EQ(r.ms(1.0), 0.7);
  EXPECT_DOUBLE_EQ(r.ms(0.8), 0.6);  // capped: the tables always get a quarter
  EXPECT_EQ(r.ms(0.0), 0);           // no budget left: no deadline to move
}

TEST(ExpansionReserve, ForgetsExpansionsOlderThanItsWindow)
{
  // Expansions get dearer as the search moves on (more agents off their goals): the
  // reserve follows the last window's, not the cheapest ever.
  ExpansionReserve r(3, 1.0);
  r.record(0.2, 1);
  for (int k = 0; k < 3; ++k) r.record(0.9, 1);
  EXPECT_DOUBLE_EQ(r.ms(5.0), 0.9);
  r.record(0.4, 1);
  EXPECT_DOUBLE_EQ(r.ms(5.0), 0.4);
}
