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

// LatencySample: the controller's per-step times over a run of any length.
TEST(LatencySample, ExactUpToItsCapLikeAVector)
{
  planner::LatencySample s(1000);
  std::vector<double> v;
  for (int i = 0; i < 1000; ++i) {
    const double x = (i * 7919) % 1000 / 10.0;
    s.push_back(x);
    v.push_back(x);
  }
  s.back() += 5;  // the controller adds to the last step (adg: the executor's share)
  v.back() += 5;
  const planner::Latency a = planner::Latency::of(s), b = planner::Latency::of(v);
  EXPECT_EQ(a.count, b.count);
  EXPECT_DOUBLE_EQ(a.mean, b.mean);
  EXPECT_EQ(a.p50, b.p50);
  EXPECT_EQ(a.p99, b.p99);
  EXPECT_EQ(a.max, b.max);
}

TEST(LatencySample, BoundedBeyondItsCapWithExactCountMeanMax)
{
  planner::LatencySample s(4096);
  const long long n = 2000000;
  for (long long i = 0; i < n; ++i) s.push_back(static_cast<double>(i % 1000));  // uniform 0..999
  s.push_back(5000);  // one outlier: max stays exact
  const planner::Latency l = planner::Latency::of(s);
  EXPECT_EQ(l.count, n + 1);
  EXPECT_NEAR(l.mean, 499.5, 0.01);
  EXPECT_EQ(l.max, 5000);
  EXPECT_NEAR(l.p50, 500, 30);  // a 4096-sample reservoir: within ~2 % of the range
  EXPECT_NEAR(l.p99, 990, 10);
}
