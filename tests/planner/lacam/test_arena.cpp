// Arena (arena.hpp): a block is raw storage and alloc() builds only what it hands out, so that
// opening a block is no O(block) step inside one real-time iteration.
#include <gtest/gtest.h>

#include "planner/lacam/arena.hpp"
#include "planner/lacam/hnode.hpp"

namespace planner {
namespace {

struct Counted {
  static inline long made = 0;
  int x = 7;
  Counted() { ++made; }
};

TEST(Arena, OpeningABlockBuildsOnlyTheObjectsHandedOut)
{
  Counted::made = 0;
  Arena<Counted> a(1 << 14);
  Counted* p = a.alloc(3);
  EXPECT_EQ(Counted::made, 3);  // not the block's 16384
  for (int k = 0; k < 3; ++k) EXPECT_EQ(p[k].x, 7);
  Counted* q = a.alloc(1 << 14);  // larger than what is left: a block of its own
  EXPECT_EQ(Counted::made, 3 + (1 << 14));
  EXPECT_EQ(q[(1 << 14) - 1].x, 7);
  EXPECT_EQ(a.bytes_reserved(), 2 * (size_t{1} << 14) * sizeof(Counted));
}

TEST(Arena, SlotsReusedAfterResetAreDefaultInitialisedAgain)
{
  Arena<Neighbor> a(8);
  Neighbor* e = a.alloc(2);
  e[0].cost = 5;
  e[1].to = reinterpret_cast<HNode*>(e);
  a.reset();
  Neighbor* f = a.alloc(2);
  ASSERT_EQ(f, e);  // the same block, reused
  EXPECT_EQ(f[0].cost, -1);
  EXPECT_EQ(f[1].to, nullptr);
}

}  // namespace
}  // namespace planner
