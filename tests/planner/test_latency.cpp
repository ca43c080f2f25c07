// Latency: one nearest-rank percentile definition for every layer's p99.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "planner/latency.hpp"

using planner::Latency;

TEST(Latency, NearestRankPercentiles)
{
  std::vector<double> v;
  for (int i = 1; i <= 100; ++i) v.push_back(i);
  std::shuffle(v.begin(), v.end(), std::mt19937(1));
  const Latency l = Latency::of(v);
  EXPECT_EQ(l.count, 100);
  EXPECT_DOUBLE_EQ(l.p50, 50);   // the 50th smallest
  EXPECT_DOUBLE_EQ(l.p99, 99);   // the 99th smallest, not the max
  EXPECT_DOUBLE_EQ(l.max, 100);
  EXPECT_DOUBLE_EQ(l.mean, 50.5);
  v.push_back(101);              // 101 samples: ceil(0.99 * 101) = 100th smallest
  EXPECT_DOUBLE_EQ(Latency::of(v).p99, 100);
}

TEST(Latency, SmallAndEmptySamples)
{
  const Latency ten = Latency::of({5, 1, 9, 3, 7, 2, 8, 4, 6, 10});
  EXPECT_DOUBLE_EQ(ten.p99, 10);  // fewer than 100 samples: p99 is the max
  EXPECT_DOUBLE_EQ(ten.p50, 5);
  const Latency one = Latency::of({0.25});
  EXPECT_DOUBLE_EQ(one.p50, 0.25);
  EXPECT_DOUBLE_EQ(one.p99, 0.25);
  const Latency none = Latency::of({});
  EXPECT_EQ(none.count, 0);
  EXPECT_DOUBLE_EQ(none.p99, 0);
  EXPECT_DOUBLE_EQ(planner::nearest_rank({3, 1, 2}, 1.0), 3);
  EXPECT_DOUBLE_EQ(planner::nearest_rank({3, 1, 2}, 0.34), 2);
  EXPECT_DOUBLE_EQ(planner::nearest_rank({}, 0.5), 0);
}
