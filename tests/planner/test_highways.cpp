// Highways (planner/highways.hpp): which arcs get a grain, the distances under those arc
// costs (DistCache::set_arc_costs), and what they do to LaCAM and RT-LaCAM* on a warehouse.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <queue>
#include <stdexcept>

#include "planner/dist_table.hpp"
#include "planner/highways.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/lacam/runner.hpp"
#include "planner/movingai.hpp"
#include "planner/validator.hpp"
#include "grid.hpp"

using namespace planner;

namespace {

// The extra cost highway_costs() gives the move w -> u (-1: no such arc).
int extra(const Graph& g, const std::vector<uint8_t>& costs, Vertex w, Vertex u)
{
  const auto in = g.in_neighbors(u);
  for (size_t k = 0; k < in.size(); ++k)
    if (in[k] == w) return costs.at(g.in_arc(u) + k);
  return -1;
}

int move(const Graph& g, const std::vector<uint8_t>& costs, int x0, int y0, int x1, int y1)
{
  return extra(g, costs, g.at(x0, y0), g.at(x1, y1));
}

// Shelf rows 1, 3, 5, 7 (x = 2..9): the aisles between them are rows 2, 4, 6, all even, and
// the frame rows 0 and 8 are 1-wide along the shelves too.
Graph shelves()
{
  return test::grid({
      "............",
      "..@@@@@@@@..",
      "............",
      "..@@@@@@@@..",
      "............",
      "..@@@@@@@@..",
      "............",
      "..@@@@@@@@..",
      "............",
  });
}

int64_t soc(const Graph& g, const Instance& ins, const std::vector<Config>& path)
{
  Validator v(g, ins.starts, ins.goals);
  for (size_t t = 1; t < path.size(); ++t) EXPECT_TRUE(v.step(path[t])) << v.error();
  return v.sum_of_costs();
}

}  // namespace

TEST(Highways, AislesGetGrainsThatAlternateByAisleNotByRowParity)
{
  const Graph g = shelves();
  const auto c = highway_costs(g, HighwayOptions{1, 3});
  ASSERT_FALSE(c.empty());
  // Lines with runs, top to bottom: rows 0, 2, 4, 6, 8 -> east, west, east, west, east.
  EXPECT_EQ(move(g, c, 3, 0, 4, 0), 0);
  EXPECT_EQ(move(g, c, 4, 0, 3, 0), 1);
  EXPECT_EQ(move(g, c, 3, 2, 4, 2), 1);
  EXPECT_EQ(move(g, c, 4, 2, 3, 2), 0);
  EXPECT_EQ(move(g, c, 3, 4, 4, 4), 0);
  EXPECT_EQ(move(g, c, 4, 4, 3, 4), 1);
  EXPECT_EQ(move(g, c, 4, 6, 3, 6), 0);
  EXPECT_EQ(move(g, c, 3, 6, 4, 6), 1);
  // The open ends (columns 0-1 and 10-11) and moves into a run keep their cost.
  EXPECT_EQ(move(g, c, 1, 2, 0, 2), 0);
  EXPECT_EQ(move(g, c, 0, 2, 1, 2), 0);
  EXPECT_EQ(move(g, c, 1, 2, 2, 2), 0);
  EXPECT_EQ(move(g, c, 1, 1, 1, 2), 0);
  // A larger penalty is that penalty.
  EXPECT_EQ(move(g, highway_costs(g, HighwayOptions{3, 3}), 3, 2, 4, 2), 3);
}

TEST(Highways, NothingWithoutLongEnoughCorridorsOrOnAGraphThatIsNotAGrid)
{
  const Graph g = shelves();
  EXPECT_TRUE(highway_costs(g, HighwayOptions{1, 9}).empty()) << "runs of 8 cells, 9 wanted";
  EXPECT_FALSE(highway_costs(g, HighwayOptions{1, 8}).empty());
  EXPECT_TRUE(highway_costs(g, HighwayOptions{0, 3}).empty()) << "penalty 0 is off";
  EXPECT_TRUE(highway_costs(test::grid({".....", ".....", "....."}), HighwayOptions{1, 3}).empty()) << "open floor";
  const Graph line = Graph::from_edges(5, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  EXPECT_TRUE(highway_costs(line, HighwayOptions{1, 1}).empty()) << "no grid view";
  // Vertical corridors get grains too, by column.
  const Graph cols = test::grid({"...", "@.@", "@.@", "@.@", "@.@", "..."});
  const auto c = highway_costs(cols, HighwayOptions{1, 3});
  ASSERT_FALSE(c.empty());
  EXPECT_EQ(move(cols, c, 1, 2, 1, 3), 0);  // column 1 is the first vertical line: south
  EXPECT_EQ(move(cols, c, 1, 3, 1, 2), 1);
}

TEST(Highways, AOneWayArcKeepsItsCost)
{
  // shelves() with row 2 (grain west) one-way east: its only moves go against the grain, and
  // there is nothing to steer; row 4 (grain east) stays two-way and keeps its grain.
  const Graph g = shelves();
  std::vector<std::pair<Vertex, Vertex>> arcs;
  std::vector<int32_t> cells;
  for (Vertex v = 0; v < g.size(); ++v) {
    cells.push_back(g.cell_y(v) * g.width() + g.cell_x(v));
    for (Vertex u : g.neighbors(v))
      if (!(g.cell_y(v) == 2 && g.cell_y(u) == 2 && g.cell_x(u) < g.cell_x(v))) arcs.push_back({v, u});
  }
  Graph d = Graph::from_arcs(g.size(), arcs);
  d.attach_grid(g.width(), g.height(), cells);
  ASSERT_TRUE(d.directed());
  const auto c = highway_costs(d, HighwayOptions{1, 3});
  ASSERT_FALSE(c.empty());
  EXPECT_EQ(move(d, c, 3, 2, 4, 2), 0) << "one-way: no penalty";
  EXPECT_EQ(move(d, c, 4, 2, 3, 2), -1) << "no such arc";
  EXPECT_EQ(move(d, c, 3, 4, 4, 4), 0);
  EXPECT_EQ(move(d, c, 4, 4, 3, 4), 1);
}

TEST(Highways, DistancesUnderArcCostsAreExactShortestPaths)
{
  const Graph g = load_map(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1.map");
  auto costs = highway_costs(g, HighwayOptions{2, 3});
  ASSERT_FALSE(costs.empty());
  auto cache = std::make_shared<DistCache>(g);
  cache->set_arc_costs(costs);
  EXPECT_TRUE(cache->arc_costs());
  DistTable d(g, cache);
  DistTable plain(g);
  const Config goals = {0, g.size() / 3, g.size() / 2, g.size() - 1};
  d.set_goals(goals);
  plain.set_goals(goals);
  int longer = 0;
  for (int i = 0; i < static_cast<int>(goals.size()); ++i) {
    // Reference: Dijkstra backwards from the goal over in-arcs, a move w -> u costing 1 + extra.
    std::vector<int32_t> ref(static_cast<size_t>(g.size()), DistTable::kInf);
    using Item = std::pair<int32_t, Vertex>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    ref[goals[i]] = 0;
    open.push({0, goals[i]});
    while (!open.empty()) {
      const auto [du, u] = open.top();
      open.pop();
      if (du != ref[u]) continue;
      const auto in = g.in_neighbors(u);
      for (size_t k = 0; k < in.size(); ++k) {
        const int32_t dw = du + 1 + costs[g.in_arc(u) + k];
        if (dw < ref[in[k]]) ref[in[k]] = dw, open.push({dw, in[k]});
      }
    }
    // Queried in a scattered order, so the lazy search is resumed many times.
    for (Vertex k = 0; k < g.size(); ++k) {
      const Vertex v = static_cast<Vertex>((static_cast<int64_t>(k) * 7919) % g.size());
      ASSERT_EQ(d.get(i, v), ref[v]) << "agent " << i << " vertex " << v;
      EXPECT_GE(d.get(i, v), plain.get(i, v));
      longer += d.get(i, v) > plain.get(i, v);
    }
  }
  EXPECT_GT(longer, 0);
  EXPECT_THROW(cache->set_arc_costs(costs), std::logic_error) << "tables exist already";
}

TEST(Highways, LacamsFirstSolutionOnAWarehouseIsCheaperAndValid)
{
  const Graph g = load_map(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1.map");
  const Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1-random-2-first200.scen", g, 200);
  int64_t cost[2] = {0, 0};
  for (int h : {0, 1}) {
    DistTable d(g);
    LacamOptions o;
    o.highways = h;
    Lacam l(g, d, o);
    EXPECT_EQ(l.highway_arcs() > 0, h > 0);
    l.reset(ins.starts, ins.goals);
    ASSERT_EQ(l.search(Budget::unlimited(), true), Status::Solved);
    cost[h] = soc(g, ins, l.path(l.goal_node()));
  }
  std::printf("LaCAM's first solution, 200 agents: standard SOC %lld without highways, %lld with\n",
              static_cast<long long>(cost[0]), static_cast<long long>(cost[1]));
  // Measured: 24217 -> 21651 (head-on meetings in the aisles are what PIBT pays for).
  EXPECT_LT(cost[1], 0.95 * cost[0]) << cost[0] << " -> " << cost[1];
}

TEST(Highways, OffWhereNoCorridorQualifies)
{
  const Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  const Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 100);
  std::vector<Config> path[2];
  for (int h : {0, 1}) {
    DistTable d(g);
    LacamOptions o;
    o.highways = h;
    Lacam l(g, d, o);
    EXPECT_EQ(l.highway_arcs(), 0u);
    l.reset(ins.starts, ins.goals);
    ASSERT_EQ(l.search(Budget::unlimited(), true), Status::Solved);
    path[h] = l.path(l.goal_node());
  }
  EXPECT_EQ(path[0], path[1]);
}

TEST(Highways, RtLacamStarExecutesAValidCheaperPlanOnAWarehouse)
{
  // Deterministic (a budget in expansions); every executed step is validated by the runner.
  const Graph g = load_map(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1.map");
  const Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1-random-2-first200.scen", g, 200);
  long long cost[2] = {0, 0};
  for (int h : {0, 1}) {
    LacamOptions o;
    o.refine = o.scatter = true;
    o.free_first = true;
    o.highways = h;
    RtLacam rt(g, ins.starts, ins.goals, o);
    RunOptions ro;
    ro.per_iteration = Budget::expansion_count(4);
    const RunResult r = run_realtime(rt, g, ins.starts, ins.goals, ro);
    ASSERT_TRUE(r.solved) << h;
    EXPECT_EQ(r.validation_error, "") << h;
    cost[h] = r.soc;
  }
  std::printf("RT-LaCAM*, 4 expansions per iteration, 200 agents: executed standard SOC %lld without highways, %lld with\n",
              cost[0], cost[1]);
  EXPECT_LT(cost[1], cost[0]) << cost[0] << " -> " << cost[1];
}
