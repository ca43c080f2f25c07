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

TEST(DistCache, HoldersThatShareACacheSearchEachGoalOnce)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  auto cache = std::make_shared<DistCache>(g);
  DistTable planner_view(g, cache), assigner_view(g);
  planner_view.set_goals({5, 9});
  assigner_view.set_goals({9, 11});
  EXPECT_EQ(assigner_view.num_tables(), 2u);  // its own cache until it shares
  assigner_view.share(cache);                  // keeps its goals, now in the shared cache
  EXPECT_EQ(cache->num_tables(), 3u);          // 5, 9, 11: vertex 9 once
  EXPECT_EQ(assigner_view.get(0, 9), 0);
  const auto d11 = bfs(g, 11);
  for (Vertex v = 0; v < g.size(); v += 7) ASSERT_EQ(assigner_view.get(1, v), d11[v]);
  // The planner's view reads the table the assigner grew: same goal, same table.
  EXPECT_EQ(planner_view.from_goal(11, 200), d11[200]);
  EXPECT_EQ(cache->num_tables(), 3u);
}

TEST(DistCache, LeastRecentlyUsedUnpinnedTablesGoFirst)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  auto cache = std::make_shared<DistCache>(g, 3);
  DistTable a(g, cache), b(g, cache);
  a.set_goals({1});
  b.set_goals({2});
  a.set_goals({3});  // 1 is unpinned now, the least recently used
  b.set_goals({4});  // 2 unpinned; 4 tables > cap 3: drop 1
  EXPECT_EQ(cache->num_tables(), 3u);
  EXPECT_FALSE(cache->contains(1));
  EXPECT_TRUE(cache->contains(2));
  a.set_goals({2});  // 2 is still cached; 3 is now the least recently used
  EXPECT_EQ(cache->num_tables(), 3u);
  b.set_goals({5});  // over the cap: 3 goes, 4 (more recent) stays
  EXPECT_FALSE(cache->contains(3));
  EXPECT_TRUE(cache->contains(4));
  // Pinned tables stay past the cap.
  a.set_goals({10, 11, 12, 13});
  EXPECT_GE(cache->num_tables(), 5u);  // four of a's + b's 5
  for (Vertex v : {10, 11, 12, 13}) EXPECT_EQ(a.from_goal(v, v), 0);
  EXPECT_EQ(b.get(0, 5), 0);
}

TEST(DistCache, PrefetchGrowsATableToWhereItWillBeQueriedFirst)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  auto cache = std::make_shared<DistCache>(g);
  Rng rng(3);
  std::vector<DistCache::Want> wants;
  for (int k = 0; k < 12; ++k)
    wants.push_back({static_cast<Vertex>(rng.below(g.size())), static_cast<Vertex>(rng.below(g.size()))});
  cache->prefetch(wants);
  EXPECT_EQ(cache->pending(), wants.size());
  // A deadline in the past: one chunk of work at most, then it reports work left.
  EXPECT_TRUE(cache->precompute(DistCache::Deadline::min()));
  EXPECT_FALSE(cache->precompute(DistCache::Deadline::max()));
  EXPECT_EQ(cache->pending(), 0u);
  for (const auto& w : wants) {
    DistCache::Table* t = cache->table(w.goal);
    const auto d = bfs(g, w.goal);
    // Discovered without growing further, and exact.
    ASSERT_EQ(t->dist[w.from], d[w.from]);
    for (Vertex u : g.neighbors(w.from)) ASSERT_EQ(t->dist[u], d[u]);
    // The rest grows lazily and stays exact.
    for (Vertex v = 0; v < g.size(); v += 5) ASSERT_EQ(t->at(v, g), d[v]);
  }
  // Met wants are not queued again.
  cache->prefetch(wants);
  EXPECT_EQ(cache->pending(), 0u);
}

TEST(DistCache, PrefetchedTablesArePinnedUntilTheNextPrefetch)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  auto cache = std::make_shared<DistCache>(g, 1);
  cache->prefetch({{7, 300}, {8, 301}});
  DistTable a(g, cache);
  a.set_goals({9});  // over the cap, but the queued tables are pinned
  EXPECT_EQ(cache->num_tables(), 3u);
  cache->prefetch({});  // queue dropped: 7 and 8 may go
  EXPECT_EQ(cache->num_tables(), 1u);
  EXPECT_EQ(a.get(0, 9), 0);
}

TEST(DistCache, PartlyGrownTablesKeepOnlyTheirFrontier)
{
  const int w = 160;
  Graph g = Graph::from_grid(w, w, std::vector<bool>(static_cast<size_t>(w) * w, true));
  DistCache cache(g);
  const Vertex goal = g.at(0, 0);
  DistCache::Table* t = cache.table(goal);
  const auto d = bfs(g, goal);
  // Half-way across: most of the discovered vertices are behind the frontier.
  ASSERT_EQ(t->at(g.at(100, 30), g), d[g.at(100, 30)]);
  EXPECT_FALSE(t->done());
  EXPECT_LT(t->queue.size(), 1000u);      // the open ring (about 130 vertices), not the 8,000 discovered
  EXPECT_LT(t->queue.capacity(), 8192u);
  EXPECT_LT(cache.bytes(), g.size() * sizeof(int32_t) + 8192 * sizeof(Vertex));
  for (Vertex v = 0; v < g.size(); v += 13) ASSERT_EQ(t->at(v, g), d[v]);
}

namespace {
// Every query on `t` past the cache's deadline: a lower bound, exact where discovered.
void expect_admissible(DistCache::Table& t, const Graph& g, const std::vector<int>& exact)
{
  for (Vertex v = 0; v < g.size(); ++v) {
    const bool known = t.exact(v);
    const int32_t d = t.at(v, g);
    if (known) {
      ASSERT_EQ(d, exact[v]) << "v " << v;
    } else {
      ASSERT_LE(d, exact[v]) << "v " << v;
      ASSERT_GE(d, 1) << "v " << v;  // 0 only on the goal
    }
  }
}
}  // namespace

TEST(DistCache, QueriesPastTheDeadlineAreLowerBoundsUntilTheTableIsComplete)
{
  // Brute force on a small grid and on a graph without coordinates (frontier bound only).
  Graph grid = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  std::vector<std::pair<Vertex, Vertex>> ring;
  for (Vertex v = 0; v < 300; ++v) ring.push_back({v, (v + 1) % 300});
  for (Vertex v = 0; v < 300; v += 7) ring.push_back({v, (v * 13 + 5) % 300});
  Graph chords = Graph::from_edges(300, ring);
  for (const Graph* gp : {&grid, &chords}) {
    const Graph& g = *gp;
    Rng rng(5);
    DistCache cache(g);
    for (int k = 0; k < 6; ++k) {
      const Vertex goal = static_cast<Vertex>(rng.below(g.size()));
      const auto exact = bfs(g, goal);
      DistCache::Table* t = cache.table(goal);
      // Grown part way (an exact query with no deadline), then the deadline passes.
      cache.set_deadline(DistCache::Deadline::max());
      const Vertex mid = static_cast<Vertex>(rng.below(g.size()));
      ASSERT_EQ(t->at(mid, g), exact[mid]);
      cache.set_deadline(DistCache::Deadline::min());
      const uint64_t pops = t->popped;
      expect_admissible(*t, g, exact);
      EXPECT_EQ(t->popped, pops) << "no query grows a table past the deadline";
      if (!t->done()) {
        EXPECT_GT(cache.counters().estimates, 0u);
        EXPECT_GT(cache.pending(), 0u);  // the table is queued for the next precompute
      }
      // Spare time grows it (to the queried vertex), later queries are exact there; the
      // complete table answers everything exactly.
      EXPECT_FALSE(cache.precompute(DistCache::Deadline::max()));
      cache.set_deadline(DistCache::Deadline::max());
      for (Vertex v = 0; v < g.size(); ++v) ASSERT_EQ(t->at(v, g), exact[v]);
      for (Vertex v = 0; v < g.size(); ++v) ASSERT_TRUE(t->exact(v));
      cache.set_deadline(DistCache::Deadline::min());
      expect_admissible(*t, g, exact);
    }
  }
}

TEST(DistCache, FreshTableBoundsAreManhattanOnGridsAndReachabilityIsExact)
{
  // Two rooms joined by nothing: the far one is unreachable (kInf once the BFS is done).
  Graph g = Graph::from_grid(7, 1, {true, true, true, false, true, true, true});
  DistCache cache(g);
  cache.set_deadline(DistCache::Deadline::min());
  DistCache::Table* t = cache.table(g.at(0, 0));
  EXPECT_EQ(t->at(g.at(0, 0), g), 0);
  EXPECT_EQ(t->at(g.at(2, 0), g), 2);  // nothing grown: Manhattan, exact on a corridor
  EXPECT_EQ(t->at(g.at(6, 0), g), 6);  // a lower bound of "unreachable"
  EXPECT_EQ(t->popped, 0u);
  cache.set_deadline(DistCache::Deadline::max());
  EXPECT_EQ(t->at(g.at(6, 0), g), DistCache::kInf);
  cache.set_deadline(DistCache::Deadline::min());
  EXPECT_EQ(t->at(g.at(5, 0), g), DistCache::kInf);  // finished: exact even past the deadline
}

// Move costs (Graph::set_move_costs: a slow lane's cells): the tables are a resumable
// Dijkstra with a bucket queue.
namespace {
// Distances to `goal`, a move onto w costing g.move_cost(w): Bellman-Ford, the slow way.
std::vector<int> weighted_reference(const Graph& g, Vertex goal)
{
  std::vector<int> d(g.size(), DistTable::kInf);
  d[goal] = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (Vertex w = 0; w < g.size(); ++w)
      if (d[w] < DistTable::kInf)
        for (Vertex u : g.in_neighbors(w))
          if (d[w] + g.move_cost(w) < d[u]) d[u] = d[w] + g.move_cost(w), changed = true;
  }
  return d;
}

Graph with_random_costs(Graph g, uint64_t seed, int top)
{
  Rng rng(seed);
  std::vector<uint8_t> c(g.size());
  for (uint8_t& k : c) k = static_cast<uint8_t>(1 + rng.below(static_cast<uint64_t>(top)));
  g.set_move_costs(c);
  return g;
}
}  // namespace

TEST(DistCache, WeightedTablesAreExactDijkstraDistancesInAnyQueryOrder)
{
  // A grid (two rooms cut apart: some goals unreachable) and a directed graph.
  Graph grid = with_random_costs(load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map"), 3, 5);
  std::vector<std::pair<Vertex, Vertex>> arcs;
  for (Vertex v = 0; v < 200; ++v) arcs.push_back({v, (v + 1) % 200}), arcs.push_back({v, (v * 7 + 3) % 200});
  arcs.erase(std::remove_if(arcs.begin(), arcs.end(), [](auto a) { return a.first == a.second; }), arcs.end());
  Graph ring = with_random_costs(Graph::from_arcs(200, arcs), 4, 9);
  ASSERT_TRUE(grid.weighted());
  ASSERT_TRUE(ring.directed());
  for (const Graph* gp : {&grid, &ring}) {
    const Graph& g = *gp;
    Rng rng(9);
    Config goals;
    for (int i = 0; i < 6; ++i) goals.push_back(static_cast<Vertex>(rng.below(g.size())));
    std::vector<std::vector<int>> exact;
    for (Vertex goal : goals) exact.push_back(weighted_reference(g, goal));
    DistTable d(g);
    d.set_goals(goals);
    for (int q = 0; q < 5000; ++q) {
      const int i = static_cast<int>(rng.below(goals.size()));
      const Vertex v = static_cast<Vertex>(rng.below(g.size()));
      ASSERT_EQ(d.get(i, v), exact[i][v]) << "goal " << goals[i] << " v " << v;
    }
    for (size_t i = 0; i < goals.size(); ++i)
      for (Vertex v = 0; v < g.size(); ++v) ASSERT_EQ(d.get(static_cast<int>(i), v), exact[i][v]);
  }
}

TEST(DistCache, WeightedQueriesPastTheDeadlineAreLowerBounds)
{
  Graph g = with_random_costs(load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map"), 5, 4);
  Rng rng(2);
  DistCache cache(g);
  for (int k = 0; k < 6; ++k) {
    const Vertex goal = static_cast<Vertex>(rng.below(g.size()));
    std::vector<int> exact = weighted_reference(g, goal);
    DistCache::Table* t = cache.table(goal);
    cache.set_deadline(DistCache::Deadline::max());
    const Vertex mid = static_cast<Vertex>(rng.below(g.size()));
    ASSERT_EQ(t->at(mid, g), exact[mid]);
    cache.set_deadline(DistCache::Deadline::min());
    expect_admissible(*t, g, exact);
    EXPECT_FALSE(cache.precompute(DistCache::Deadline::max()));
    cache.set_deadline(DistCache::Deadline::max());
    for (Vertex v = 0; v < g.size(); ++v) ASSERT_EQ(t->at(v, g), exact[v]);
  }
}

TEST(DistCache, UnitCostsKeepThePlainBfsAndBadCostsAreRefused)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  g.set_move_costs(std::vector<uint8_t>(g.size(), 1));
  EXPECT_FALSE(g.weighted());  // all 1: no costs at all
  DistCache cache(g);
  EXPECT_FALSE(cache.table(0)->weighted);
  EXPECT_THROW(g.set_move_costs(std::vector<uint8_t>(3, 2)), std::invalid_argument);
  std::vector<uint8_t> zero(g.size(), 1);
  zero[5] = 0;
  EXPECT_THROW(g.set_move_costs(zero), std::invalid_argument);
}
