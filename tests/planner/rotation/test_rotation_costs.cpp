// Move costs (Graph::set_move_costs: slow lanes) in the rotation planners: RotationDist
// measures a forward move into a cell at its guidance cost plus the cell's extra steps
// (turns keep theirs), checked against a forward Dijkstra; and pibt-rot, epibt, wppl route round a slow
// shortcut when the detour is cheaper, and take it when the costs are off.
#include <gtest/gtest.h>

#include <functional>
#include <queue>
#include <vector>

#include "planner/blocked.hpp"
#include "planner/heading.hpp"
#include "planner/rng.hpp"
#include "planner/rotation/guidance.hpp"
#include "planner/rotation/rotation_dist.hpp"
#include "planner/solver.hpp"
#include "planner/validator.hpp"
#include "grid.hpp"

using planner::Config;
using planner::Graph;
using planner::Guidance;
using planner::RotationDist;
using planner::Vertex;

namespace {

// Forward Dijkstra over (cell, heading) from (v, o) to any state on `goal`: F into the cell
// ahead (along an arc) costs forward(cell, heading) + (move_cost(cell ahead) - 1) x the
// cheapest forward cost, a quarter turn `turn`. kInf when the goal cannot be reached.
uint32_t brute(const Graph& g, const Guidance& gd, Vertex v, int o, Vertex goal)
{
  using Item = std::pair<uint32_t, int>;
  std::vector<uint32_t> d(static_cast<size_t>(g.size()) * 4, UINT32_MAX);
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  d[static_cast<size_t>(v) * 4 + o] = 0;
  q.push({0, v * 4 + o});
  while (!q.empty()) {
    const auto [k, s] = q.top();
    q.pop();
    if (k != d[static_cast<size_t>(s)]) continue;
    const Vertex u = s / 4;
    const int h = s % 4;
    if (u == goal) return k;
    const Vertex f = planner::cell_ahead(g, u, h);
    const uint32_t extra = f >= 0 ? static_cast<uint32_t>(g.move_cost(f) - 1) * gd.min_forward() : 0;
    const Item next[3] = {{f >= 0 ? k + gd.forward_cost(u, h) + extra : UINT32_MAX, f * 4 + h},
                          {k + gd.turn, u * 4 + (h + 1) % 4},
                          {k + gd.turn, u * 4 + (h + 3) % 4}};
    for (const auto& [nk, n] : next)
      if (nk != UINT32_MAX && nk < d[static_cast<size_t>(n)]) d[static_cast<size_t>(n)] = nk, q.push({nk, n});
  }
  return RotationDist::kInf;
}

// A random grid with random one-way arcs (a quarter of the arcs dropped) and move costs 1..4.
Graph weighted_directed(uint64_t seed)
{
  planner::Rng rng(seed + 11);
  const Graph full = test::random_grid(8, 6, 15, seed + 40);
  Graph g = planner::without_arcs(full, [&](Vertex, Vertex) { return rng.below(4) == 0; });
  std::vector<uint8_t> cost(static_cast<size_t>(g.size()));
  for (uint8_t& c : cost) c = static_cast<uint8_t>(1 + rng.below(4));
  g.set_move_costs(cost);
  return g;
}

}  // namespace

// The tables equal a forward Dijkstra in the move costs, with and without arrow guidance
// (whose forward costs the move costs' extra steps are added to). Fails if RotationDist ignores the costs.
TEST(RotationCosts, DistEqualsDijkstraOnRandomWeightedDirectedGrids)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = weighted_directed(seed);
    ASSERT_TRUE(g.weighted());
    for (bool guided : {false, true}) {
      RotationDist dist(g);
      Guidance gd;
      if (guided) {
        gd = planner::arrow_guidance(g, 2, 5, 2);  // cheapest forward 2: a step's extra costs 2
        dist.set_guidance(gd);
      }
      long differs = 0;  // states whose costed distance differs from the uncosted one
      for (Vertex goal = 0; goal < g.size(); goal += 3) {
        RotationDist::Table* t = dist.table(goal);
        for (Vertex v = g.size() - 1; v >= 0; --v)
          for (int o = 0; o < 4; ++o) {
            const uint32_t want = brute(g, gd, v, o, goal);
            ASSERT_EQ(dist.get(t, v, o), want) << "seed " << seed << " guided " << guided << " goal " << goal << " v " << v << " o " << o;
          }
      }
      // Switched off, the tables are the uncosted ones again.
      dist.set_move_costs(false);
      Graph plain = planner::without_arcs(g, [](Vertex, Vertex) { return false; });
      plain.set_move_costs(std::vector<uint8_t>(static_cast<size_t>(g.size()), 1));
      for (Vertex goal = 1; goal < g.size(); goal += 5) {
        RotationDist::Table* t = dist.table(goal);
        for (Vertex v = 0; v < g.size(); ++v)
          for (int o = 0; o < 4; ++o) {
            const uint32_t want = brute(plain, gd, v, o, goal);
            ASSERT_EQ(dist.get(t, v, o), want) << "costs off: seed " << seed << " goal " << goal;
            differs += want != brute(g, gd, v, o, goal);
          }
      }
      EXPECT_GT(differs, 0) << "seed " << seed << ": the costs should change some distances";
    }
  }
}

// One robot from the top-left corner (facing east) to the top-right one. Along the top row
// it is 4 forward moves, but the three cells between are a slow lane (cost 5: 16 in all);
// round the bottom it is 11 steps at cost 1 (2 turns more on each side). With the costs
// every rotation solver goes round; without, along the top.
TEST(RotationCosts, RotationSolversRouteRoundASlowShortcut)
{
  auto route = [](planner::Solver kind, bool costs) {
    Graph g = test::grid({".....", ".@@@.", "....."});
    if (costs) {
      std::vector<uint8_t> c(static_cast<size_t>(g.size()), 1);
      for (int x = 1; x <= 3; ++x) c[static_cast<size_t>(g.at(x, 0))] = 5;
      g.set_move_costs(c);
    }
    const Config s = {g.at(0, 0)}, t = {g.at(4, 0)};
    planner::SolverOptions opt;
    opt.headings = {0};
    opt.epibt.priority = planner::EpibtOptions::Priority::Age;
    auto p = planner::make_planner(kind, g, s, t, opt);
    bool top = false;  // the robot crossed the slow middle of the top row
    Config cur = s;
    for (int step = 0; step < 40 && cur[0] != t[0]; ++step) {
      p->search(planner::Budget{});
      const Config next = p->next();
      EXPECT_EQ(planner::Validator::check_transition(g, cur, next), "");
      p->commit();
      cur = p->current();
      top = top || cur[0] == g.at(2, 0);
    }
    EXPECT_EQ(cur[0], t[0]) << planner::to_string(kind) << (costs ? " with" : " without") << " costs: never arrived";
    return top;
  };
  for (planner::Solver kind : {planner::Solver::PibtRot, planner::Solver::Epibt, planner::Solver::Wppl}) {
    EXPECT_TRUE(route(kind, false)) << planner::to_string(kind) << ": without costs the short top row is the way";
    EXPECT_FALSE(route(kind, true)) << planner::to_string(kind) << ": the slow top row was taken";
  }
}
