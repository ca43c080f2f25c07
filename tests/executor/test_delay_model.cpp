// DelayModel: reproducible by seed, the configured rates and durations, checks.
#include <gtest/gtest.h>

#include "executor/delay_model.hpp"

using executor::DelayModel;
using executor::DelaySpec;

TEST(DelayModel, SameSeedSameStopsOtherSeedOtherStops)
{
  DelaySpec s;
  s.kind = "bernoulli";
  s.p = 0.05;
  s.min_ticks = 1;
  s.max_ticks = 5;
  auto trace = [&](uint64_t seed) {
    s.seed = seed;
    DelayModel m(s, 20);
    std::vector<char> t;
    for (int k = 0; k < 200; ++k) {
      m.tick(k);
      for (int i = 0; i < 20; ++i) t.push_back(m.stopped(i));
    }
    return t;
  };
  EXPECT_EQ(trace(3), trace(3));
  EXPECT_NE(trace(3), trace(4));
}

TEST(DelayModel, BernoulliRateAndDurationsMatchTheSpec)
{
  DelaySpec s;
  s.kind = "bernoulli";
  s.p = 0.01;
  s.min_ticks = 2;
  s.max_ticks = 6;
  const int n = 100, ticks = 5000;
  DelayModel m(s, n);
  std::vector<long long> run(n, 0);
  long long min_len = 1 << 30, max_len = 0;
  for (int k = 0; k < ticks; ++k) {
    m.tick(k);
    for (int i = 0; i < n; ++i) {
      if (m.stopped(i)) {
        ++run[i];
      } else if (run[i] > 0) {
        min_len = std::min(min_len, run[i]);
        max_len = std::max(max_len, run[i]);
        run[i] = 0;
      }
    }
  }
  // A stop of length L can be followed at once by another: runs are sums of stops.
  EXPECT_GE(min_len, 2);
  EXPECT_LE(m.stop_ticks(), n * static_cast<long long>(ticks));
  // Expected starts: p per free agent-tick, ~ p * n * ticks / (1 + p * 4) = ~4800.
  EXPECT_GT(m.stops(), 4000);
  EXPECT_LT(m.stops(), 5600);
  EXPECT_GE(max_len, 6);
}

TEST(DelayModel, PoissonFractionSlowdownAndStuck)
{
  DelaySpec s;
  s.kind = "poisson";
  s.rate = 0.5;
  s.fraction = 0.1;
  s.slow = {{3, 0.7}};
  s.stuck = {{7, 10, 60}};
  const int n = 50;
  DelayModel m(s, n);
  EXPECT_EQ(m.move_ticks(3), 2);
  EXPECT_EQ(m.move_ticks(0), 1);
  std::vector<char> ever(n, 0);
  for (int k = 0; k < 100; ++k) {
    m.tick(k);
    for (int i = 0; i < n; ++i) ever[i] |= m.stopped(i);
    if (k >= 10 && k < 70) {
      EXPECT_TRUE(m.stopped(7)) << k;
    }
  }
  int stoppers = 0;
  for (int i = 0; i < n; ++i) stoppers += ever[i] && i != 7;
  EXPECT_GE(stoppers, 1);
  EXPECT_LE(stoppers, 15);  // ~10 % of 50 agents
}

TEST(DelayModel, CheckNamesTheBadKey)
{
  const int n = 4;
  DelaySpec s;
  EXPECT_EQ(executor::check(s, n), "");
  s.p = 1.5;
  EXPECT_EQ(executor::check(s, n).rfind("p: ", 0), 0u);
  s = {};
  s.kind = "gauss";
  EXPECT_EQ(executor::check(s, n).rfind("kind: ", 0), 0u);
  s = {};
  s.min_ticks = 3;
  s.max_ticks = 2;
  EXPECT_EQ(executor::check(s, n).rfind("duration: ", 0), 0u);
  s = {};
  s.rate = -1;
  EXPECT_EQ(executor::check(s, n).rfind("rate: ", 0), 0u);
  s = {};
  s.fraction = 0;
  EXPECT_EQ(executor::check(s, n).rfind("fraction: ", 0), 0u);
  s = {};
  s.slow = {{0, 0}};
  EXPECT_EQ(executor::check(s, n).rfind("slow: ", 0), 0u);
  s = {};
  s.stuck = {{9, 0, 5}};
  EXPECT_EQ(executor::check(s, n).rfind("stuck: ", 0), 0u);
}
