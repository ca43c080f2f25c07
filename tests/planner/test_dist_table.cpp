#include <gtest/gtest.h>

#include <queue>

#include "planner/dist_table.hpp"
#include "planner/movingai.hpp"
#include "planner/rng.hpp"

using namespace planner;

namespace {
std::vector<int> bfs(const Graph& g, Vertex s)
{
  std::vector<int> d(g.size(), DistTable::kInf);
  std::queue<Vertex> q;
  d[s] = 0;
  q.push(s);
  while (!q.empty()) {
    Vertex v = q.front();
    q.pop();
    for (Vertex u : g.neighbors(v))
      if (d[u] == DistTable::kInf) d[u] = d[v] + 1, q.push(u);
  }
  return d;
}
}  // namespace

TEST(DistTable, LazyBfsMatchesFullBfsInAnyQueryOrder)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Rng rng(7);
  Config goals;
  for (int i = 0; i < 20; ++i) goals.push_back(static_cast<Vertex>(rng.below(g.size())));
  DistTable d(g);
  d.set_goals(goals);
  for (int q = 0; q < 20000; ++q) {
    int i = static_cast<int>(rng.below(20));
    Vertex v = static_cast<Vertex>(rng.below(g.size()));
    ASSERT_EQ(d.get(i, v), bfs(g, goals[i])[v]);
  }
}

TEST(DistTable, TablesAreSharedPerGoalVertex)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  DistTable d(g);
  d.set_goals({5, 5, 9, 5});
  EXPECT_EQ(d.num_tables(), 2u);
  d.set_goals({9, 5, 11, 5});  // lifelong goal change: only vertex 11 is new
  EXPECT_EQ(d.num_tables(), 3u);
  EXPECT_EQ(d.get(2, 11), 0);
}

TEST(DistTable, UnreachableIsInfinite)
{
  std::vector<bool> free = {true, true, false, true};
  Graph g = Graph::from_grid(4, 1, free);
  DistTable d(g);
  d.set_goals({0});
  EXPECT_EQ(d.get(0, 1), 1);
  EXPECT_EQ(d.get(0, 2), DistTable::kInf);
}

TEST(DistTable, CapDropsIdleTablesAndStaysCorrect)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  const size_t cap = 8;
  DistTable d(g, cap);
  Rng rng(11);
  for (int round = 0; round < 10 * static_cast<int>(cap); ++round) {
    Config goals = {static_cast<Vertex>(rng.below(g.size())), static_cast<Vertex>(rng.below(g.size())),
                    static_cast<Vertex>(rng.below(g.size()))};
    d.set_goals(goals);
    EXPECT_LE(d.num_tables(), cap);
    for (int q = 0; q < 20; ++q) {
      int i = static_cast<int>(rng.below(3));
      Vertex v = static_cast<Vertex>(rng.below(g.size()));
      ASSERT_EQ(d.get(i, v), bfs(g, goals[i])[v]);
    }
  }
  // Tables in use are never dropped, even past the cap.
  Config many;
  for (Vertex v = 0; v < 20; ++v) many.push_back(v);
  d.set_goals(many);
  EXPECT_EQ(d.num_tables(), 20u);
  EXPECT_EQ(d.get(19, 19), 0);
}
