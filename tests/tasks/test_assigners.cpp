// Assigners: Hungarian is optimal (brute force over all injections on small random
// matrices, square and rectangular); greedy takes the cheapest free task in agent order;
// the k-nearest restriction is exact when k covers every task.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

#include "tasks/greedy_assigner.hpp"
#include "tasks/hungarian.hpp"
#include "tasks/hungarian_assigner.hpp"

using namespace tasks;

namespace {

// Minimum total cost matching min(rows, cols) pairs, by brute force over permutations.
int64_t brute_force(int rows, int cols, const std::vector<int64_t>& c)
{
  const bool t = rows > cols;  // enumerate over the larger side
  const int n = t ? cols : rows, m = t ? rows : cols;
  auto at = [&](int i, int j) { return t ? c[static_cast<size_t>(j) * cols + i] : c[static_cast<size_t>(i) * cols + j]; };
  std::vector<int> perm(m);
  std::iota(perm.begin(), perm.end(), 0);
  int64_t best = std::numeric_limits<int64_t>::max();
  do {
    int64_t s = 0;
    for (int i = 0; i < n; ++i) s += at(i, perm[i]);
    best = std::min(best, s);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

int64_t total(int cols, const std::vector<int64_t>& c, const std::vector<int>& a)
{
  int64_t s = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] >= 0) s += c[i * cols + a[i]];
  return s;
}

void expect_valid(int rows, int cols, const std::vector<int>& a)
{
  ASSERT_EQ(static_cast<int>(a.size()), rows);
  std::vector<int> used(cols, 0);
  int matched = 0;
  for (int x : a)
    if (x >= 0) {
      ASSERT_LT(x, cols);
      EXPECT_EQ(used[x]++, 0) << "column used twice";
      ++matched;
    }
  EXPECT_EQ(matched, std::min(rows, cols));
}

}  // namespace

TEST(Hungarian, OptimalAgainstBruteForce)
{
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 400; ++trial) {
    const int rows = 1 + static_cast<int>(rng() % 6), cols = 1 + static_cast<int>(rng() % 6);
    const int range = trial % 3 == 0 ? 3 : 100;  // small ranges: many ties
    std::vector<int64_t> c(static_cast<size_t>(rows) * cols);
    for (auto& x : c) x = static_cast<int64_t>(rng() % range);
    const auto a = min_cost_assignment(rows, cols, c);
    expect_valid(rows, cols, a);
    EXPECT_EQ(total(cols, c, a), brute_force(rows, cols, c)) << "trial " << trial << " " << rows << "x" << cols;
  }
}

TEST(Hungarian, KnownMatrixAndEdgeCases)
{
  // 3 x 3 with the unique optimum 1 + 2 + 2 = 5: rows take columns 1, 0, 2.
  const std::vector<int64_t> c{4, 1, 3, 2, 0, 5, 3, 2, 2};
  const auto a = min_cost_assignment(3, 3, c);
  EXPECT_EQ(a, (std::vector<int>{1, 0, 2}));
  EXPECT_EQ(total(3, c, a), 5);
  EXPECT_TRUE(min_cost_assignment(0, 3, {}).empty());
  EXPECT_EQ(min_cost_assignment(2, 0, {}), (std::vector<int>{-1, -1}));
  EXPECT_THROW(min_cost_assignment(2, 2, {1, 2, 3}), std::invalid_argument);
  // Large costs (graph distances on big maps) do not overflow.
  const int64_t big = int64_t{1} << 40;
  EXPECT_EQ(min_cost_assignment(2, 2, {big, 0, 0, big}), (std::vector<int>{1, 0}));
}

TEST(GreedyAssigner, CheapestFreeTaskInAgentOrder)
{
  // Row 0 takes column 0 (cost 1) although row 1 needs it more; row 1 gets column 1.
  const std::vector<int64_t> c{1, 2, 1, 100};
  GreedyAssigner g;
  EXPECT_EQ(g.assign(2, 2, [&](int i, int j) { return c[i * 2 + j]; }), (std::vector<int>{0, 1}));
  // Ties: the lower column (older task).
  EXPECT_EQ(g.assign(1, 3, [](int, int j) { return j == 0 ? 5 : 3; }), (std::vector<int>{1}));
  // More agents than tasks: the last ones get none.
  EXPECT_EQ(g.assign(3, 1, [](int, int) { return 1; }), (std::vector<int>{0, -1, -1}));
}

TEST(HungarianAssigner, ExactWhenCandidatesCoverEverything)
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    const int rows = 1 + static_cast<int>(rng() % 6), cols = 1 + static_cast<int>(rng() % 6);
    std::vector<int64_t> c(static_cast<size_t>(rows) * cols);
    for (auto& x : c) x = static_cast<int64_t>(rng() % 50);
    HungarianAssigner h(/*k_nearest=*/cols);
    const auto a = h.assign(rows, cols, [&](int i, int j) { return c[static_cast<size_t>(i) * cols + j]; });
    expect_valid(rows, cols, a);
    EXPECT_EQ(total(cols, c, a), brute_force(rows, cols, c));
  }
}

TEST(HungarianAssigner, KNearestAndBatchesStayValid)
{
  // 300 agents, 450 tasks, 4 candidates each, batches of 64: a valid full matching, never
  // worse than greedy on these random costs by much, and each row within its candidates
  // unless its candidates were taken by an earlier batch.
  std::mt19937 rng(3);
  const int rows = 300, cols = 450;
  std::vector<int64_t> c(static_cast<size_t>(rows) * cols);
  for (auto& x : c) x = static_cast<int64_t>(rng() % 1000);
  auto cost = [&](int i, int j) { return c[static_cast<size_t>(i) * cols + j]; };
  HungarianAssigner h(4, 64);
  const auto a = h.assign(rows, cols, cost);
  expect_valid(rows, cols, a);
  GreedyAssigner g;
  const auto b = g.assign(rows, cols, cost);
  EXPECT_LE(total(cols, c, a), total(cols, c, b));
}

TEST(Assigner, Factory)
{
  EXPECT_EQ(make_assigner("greedy")->name(), "greedy");
  EXPECT_EQ(make_assigner("hungarian")->name(), "hungarian");
  EXPECT_THROW(make_assigner("auction"), std::invalid_argument);
}
