// Guidance for the rotation action model: guided RotationDist tables against a brute-force
// Dijkstra, the arrow field's reachability and cheap-arc connectivity, the text format's
// errors and round trip, bounded (deadline) queries, and pibt-rot steps under guidance.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <queue>
#include <string>
#include <vector>

#include "planner/error.hpp"
#include "planner/rotation/guidance.hpp"
#include "planner/rng.hpp"
#include "planner/rotation/rotation_dist.hpp"
#include "planner/rotation/rotation_pibt.hpp"
#include "planner/validator.hpp"
#include "grid.hpp"

using planner::Config;
using planner::Graph;
using planner::Guidance;
using planner::RotationDist;
using planner::RotationPibt;
using planner::Vertex;

namespace {

using test::random_grid;

Guidance random_guidance(const Graph& g, uint64_t seed, int max_cost)
{
  planner::Rng rng(seed);
  Guidance gd;
  gd.turn = static_cast<uint16_t>(1 + rng.below(static_cast<uint32_t>(max_cost)));
  gd.forward.resize(static_cast<size_t>(g.size()) * 4);
  for (auto& c : gd.forward) c = static_cast<uint16_t>(1 + rng.below(static_cast<uint32_t>(max_cost)));
  return gd;
}

// Brute force: forward Dijkstra over (cell, heading) from (v, o) with the MAPF_T actions
// and the guidance's costs, until a state on `goal`; kInf when none is reachable.
uint32_t brute(const Graph& g, const Guidance& gd, Vertex v, int o, Vertex goal)
{
  static const int dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
  std::vector<uint32_t> d(static_cast<size_t>(g.size()) * 4, UINT32_MAX);
  using Item = std::pair<uint32_t, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  d[static_cast<size_t>(v * 4 + o)] = 0;
  q.push({0, v * 4 + o});
  while (!q.empty()) {
    const auto [c, s] = q.top();
    q.pop();
    if (c != d[static_cast<size_t>(s)]) continue;
    const Vertex u = s / 4;
    const int h = s % 4;
    if (u == goal) return c;
    const Vertex f = g.at(g.cell_x(u) + dx[h], g.cell_y(u) + dy[h]);
    const std::pair<int, uint32_t> next[3] = {{f >= 0 ? f * 4 + h : -1, gd.forward_cost(u, h)},
                                              {u * 4 + (h + 1) % 4, gd.turn},
                                              {u * 4 + (h + 3) % 4, gd.turn}};
    for (auto [n, w] : next)
      if (n >= 0 && c + w < d[static_cast<size_t>(n)]) d[static_cast<size_t>(n)] = c + w, q.push({c + w, n});
  }
  return RotationDist::kInf;
}

std::string write_file(const std::string& name, const std::string& text)
{
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string load_error(const Graph& g, const std::string& text)
{
  const std::string path = write_file("guidance_bad.txt", text);
  try {
    planner::load_guidance(g, path);
  } catch (const planner::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Guidance, WeightedRotationDistEqualsBruteForceDijkstra)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = random_grid(8, 6, 20, seed + 40);
    const Guidance gd = random_guidance(g, seed, seed % 2 ? 9 : 3);
    RotationDist dist(g);
    dist.set_guidance(gd);
    ASSERT_TRUE(dist.weighted());
    for (Vertex goal = 0; goal < g.size(); goal += 2) {
      RotationDist::Table* t = dist.table(goal);
      // A scattered order: the lazy Dijkstra must be exact whatever it was grown for.
      for (Vertex v = g.size() - 1; v >= 0; --v)
        for (int o = 0; o < 4; ++o)
          ASSERT_EQ(dist.get(t, v, o), brute(g, gd, v, o, goal)) << "seed " << seed << " goal " << goal << " v " << v << " o " << o;
    }
  }
}

TEST(Guidance, UniformGuidanceKeepsTheBfsAndItsDistances)
{
  const Graph g = random_grid(7, 7, 15, 5);
  RotationDist plain(g), guided(g);
  Guidance ones;
  ones.forward.assign(static_cast<size_t>(g.size()) * 4, 1);
  guided.set_guidance(ones);
  EXPECT_FALSE(guided.weighted());
  for (Vertex goal = 0; goal < g.size(); goal += 5)
    for (Vertex v = 0; v < g.size(); ++v)
      for (int o = 0; o < 4; ++o) ASSERT_EQ(guided.get(guided.table(goal), v, o), plain.get(plain.table(goal), v, o));
  Guidance bad;
  bad.forward.assign(3, 1);
  EXPECT_THROW(guided.set_guidance(bad), std::invalid_argument);
}

TEST(Guidance, ArrowFieldKeepsEveryStateReachingEveryGoalOnCheapConnectedLanes)
{
  for (uint64_t seed = 0; seed < 6; ++seed) {
    const Graph g = random_grid(11, 9, 25, seed + 70);  // dead ends and pockets
    const Guidance gd = planner::arrow_guidance(g, 1, 4, 2);
    ASSERT_EQ(gd.forward.size(), static_cast<size_t>(g.size()) * 4);
    EXPECT_TRUE(planner::cheap_arcs_strongly_connected(g, gd, 1)) << "seed " << seed;
    long against = 0;
    for (uint16_t c : gd.forward) against += c == 4;
    EXPECT_GT(against, 0) << "the field has costly arcs";  // not repaired into uniform costs
    RotationDist plain(g), guided(g);
    guided.set_guidance(gd);
    for (Vertex goal = 0; goal < g.size(); ++goal) {
      RotationDist::Table *tp = plain.table(goal), *tg = guided.table(goal);
      for (Vertex v = 0; v < g.size(); ++v)
        for (int o = 0; o < 4; ++o)
          ASSERT_EQ(plain.get(tp, v, o) == RotationDist::kInf, guided.get(tg, v, o) == RotationDist::kInf)
              << "seed " << seed << " goal " << goal << " v " << v << " o " << o;
    }
  }
  // Without the repair an alternating field strands cells: a dead end entered against its
  // arrow only. The raw field on this map is not strongly connected on cheap arcs.
  const Graph d = test::grid({"....", ".@@@", "....", "@@@."});
  Guidance raw = planner::arrow_guidance(d, 1, 1, 1);  // costs all 1: no repair ran
  for (Vertex v = 0; v < d.size(); ++v)
    for (int o = 0; o < 4; ++o) {
      const bool with = o % 2 == 0 ? (o == 0) == (d.cell_y(v) % 2 == 0) : (o == 1) == (d.cell_x(v) % 2 == 0);
      raw.forward[static_cast<size_t>(v) * 4 + o] = with ? 1 : 5;
    }
  EXPECT_FALSE(planner::cheap_arcs_strongly_connected(d, raw, 1));
  EXPECT_TRUE(planner::cheap_arcs_strongly_connected(d, planner::arrow_guidance(d, 1, 5, 1), 1));
  EXPECT_THROW(planner::arrow_guidance(d, 0, 3, 1), std::invalid_argument);
  EXPECT_THROW(planner::arrow_guidance(d, 1, Guidance::kMaxCost + 1, 1), std::invalid_argument);
}

// Aisles four columns apart (a gridified SUMO warehouse: cross aisles on rows 0 and 4,
// picking aisles on columns 0, 4, 8, 12). By coordinate parity every aisle would point
// south and the repair would have made them all cheap both ways; numbered as lanes they
// alternate, and the field keeps one cheap direction per aisle.
TEST(Guidance, ArrowFieldAlternatesBetweenAislesAnyDistanceApart)
{
  const Graph g = test::grid({".............", ".@@@.@@@.@@@.", ".@@@.@@@.@@@.", ".@@@.@@@.@@@.", "............."});
  const Guidance gd = planner::arrow_guidance(g, 1, 4, 2);
  EXPECT_TRUE(planner::cheap_arcs_strongly_connected(g, gd, 1));
  for (int x : {4, 8}) {  // the inner aisles (the outer ones close the loop: the repair may touch them)
    const Vertex v = g.at(x, 2);
    ASSERT_GE(v, 0);
    const bool south = (x / 4) % 2 == 0;  // aisle 0 south, 1 north, ...
    EXPECT_EQ(gd.forward_cost(v, 1), south ? 1 : 4) << "aisle at x " << x << " facing south";
    EXPECT_EQ(gd.forward_cost(v, 3), south ? 4 : 1) << "aisle at x " << x << " facing north";
  }
  EXPECT_EQ(gd.forward_cost(g.at(6, 0), 0), 1);  // row 0 east
  EXPECT_EQ(gd.forward_cost(g.at(6, 0), 2), 4);
  EXPECT_EQ(gd.forward_cost(g.at(6, 4), 2), 1);  // row 4 (the next lane) west
  EXPECT_EQ(gd.forward_cost(g.at(6, 4), 0), 4);
  // Every row and column a lane: the parity field (even y east, even x south), so LoRR's
  // maps keep the field they were measured with.
  const Graph full = random_grid(9, 7, 0, 3);
  const Guidance pf = planner::arrow_guidance(full, 1, 4, 2);
  for (Vertex v = 0; v < full.size(); ++v) {
    EXPECT_EQ(pf.forward_cost(v, 0), full.cell_y(v) % 2 == 0 ? 1 : 4) << v;
    EXPECT_EQ(pf.forward_cost(v, 1), full.cell_x(v) % 2 == 0 ? 1 : 4) << v;
  }
}

TEST(Guidance, FileRoundTripsAndErrorsNameFileAndLine)
{
  const Graph g = random_grid(6, 5, 10, 9);
  const Guidance gd = planner::arrow_guidance(g, 2, 6, 2);
  const std::string path = ::testing::TempDir() + "guidance_rt.txt";
  planner::save_guidance(g, gd, path);
  const Guidance back = planner::load_guidance(g, path);
  EXPECT_EQ(back.turn, gd.turn);
  EXPECT_EQ(back.forward, gd.forward);
  // Defaults and comments; unlisted cells take `default`.
  const Vertex v0 = g.at(g.cell_x(0), g.cell_y(0));
  const std::string ok = "# a comment\nturn 3\ndefault 2\n" + std::to_string(g.cell_x(v0)) + " " + std::to_string(g.cell_y(v0)) +
                         " 1 4 5 6  # east south west north\n";
  const Guidance small = planner::load_guidance(g, write_file("guidance_ok.txt", ok));
  EXPECT_EQ(small.turn, 3);
  EXPECT_EQ(small.forward_cost(v0, 0), 1);
  EXPECT_EQ(small.forward_cost(v0, 3), 6);
  EXPECT_EQ(small.forward_cost(g.size() - 1, 2), 2);

  const std::string p = ::testing::TempDir() + "guidance_bad.txt";
  Vertex wall = -1;
  for (int y = 0; y < g.height() && wall < 0; ++y)
    for (int x = 0; x < g.width(); ++x)
      if (g.at(x, y) < 0) {
        EXPECT_EQ(load_error(g, "turn 1\n\n" + std::to_string(x) + " " + std::to_string(y) + " 1 1 1 1\n"),
                  p + ":3: cell (" + std::to_string(x) + ", " + std::to_string(y) + ") is off the map or an obstacle");
        wall = 0;
        break;
      }
  ASSERT_EQ(wall, 0) << "the test map has an obstacle";
  const std::string c0 = std::to_string(g.cell_x(v0)) + " " + std::to_string(g.cell_y(v0));
  EXPECT_EQ(load_error(g, "turn 0\n"), p + ":1: turn cost 0 out of range 1.." + std::to_string(Guidance::kMaxCost));
  EXPECT_EQ(load_error(g, "# x\nturn two\n"), p + ":2: turn cost: 'two' is not an integer");
  EXPECT_EQ(load_error(g, c0 + " 1 1 1\n"), p + ":1: expected 'X Y COST_E COST_S COST_W COST_N', 'turn COST' or 'default COST'");
  EXPECT_EQ(load_error(g, c0 + " 1 1 1 1\n" + c0 + " 2 2 2 2\n"), p + ":2: cell (" + c0.substr(0, c0.find(' ')) + ", " +
                                                                      c0.substr(c0.find(' ') + 1) + ") listed twice");
  EXPECT_EQ(load_error(g, c0 + " 1 1 99 1\n"), p + ":1: cost west 99 out of range 1.." + std::to_string(Guidance::kMaxCost));
  EXPECT_EQ(load_error(g, "9999 1 1 1 1 1\n"), p + ":1: cell (9999, 1) is off the map or an obstacle");
  EXPECT_EQ(load_error(g, "default\n"), p + ":1: expected 'default COST'");
  const std::string missing = ::testing::TempDir() + "no_such_guidance.txt";
  EXPECT_THROW(planner::load_guidance(g, missing), planner::InputError);
}

TEST(Guidance, BoundedQueriesAreLowerBoundsUntilCompleteThenExact)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = random_grid(10, 8, 15, seed + 90);
    const bool weighted = seed % 2 == 1;
    const Guidance gd = weighted ? planner::arrow_guidance(g, 2, 6, 2) : Guidance{};
    RotationDist dist(g);
    dist.set_guidance(gd);
    Vertex goal = g.size() / 2;
    while (g.degree(goal) < 2) ++goal;
    RotationDist::Table* t = dist.table(goal);
    dist.pin(t);
    // Exact near the goal before the deadline: grow a little, then the deadline passes.
    const Vertex near = g.neighbors(goal)[0];
    EXPECT_EQ(dist.get(t, near, 0), brute(g, gd, near, 0, goal));
    dist.set_deadline(std::chrono::steady_clock::now() - std::chrono::seconds(1));
    long bounded = 0;
    for (Vertex v = 0; v < g.size(); ++v)
      for (int o = 0; o < 4; ++o) {
        const uint32_t exact = brute(g, gd, v, o, goal);
        const uint16_t got = dist.get(t, v, o);
        ASSERT_LE(got, exact) << "seed " << seed << " v " << v << " o " << o;  // kInf exact: any answer
        if (v != goal) {
          ASSERT_GT(got, 0) << "never 0 off the goal";
        }
        bounded += got != exact;
      }
    EXPECT_GT(bounded, 0) << "the deadline stopped the search";
    EXPECT_FALSE(t->done());
    EXPECT_EQ(dist.pending(), 1u);  // queued for precompute
    EXPECT_GT(dist.bounded_answers(), 0u);
    EXPECT_FALSE(dist.precompute(std::chrono::steady_clock::time_point::max()));
    EXPECT_TRUE(t->done());
    EXPECT_EQ(dist.pending(), 0u);
    for (Vertex v = 0; v < g.size(); ++v)
      for (int o = 0; o < 4; ++o) ASSERT_EQ(dist.get(t, v, o), brute(g, gd, v, o, goal));
    // A late table nobody holds any more (its agent's goal changed) is dropped unfinished.
    RotationDist::Table* gone = dist.table(g.size() - 1);
    EXPECT_LE(dist.get(gone, 0, 0), brute(g, gd, 0, 0, g.size() - 1));  // a bound: the deadline passed
    EXPECT_EQ(dist.pending(), 1u);
    EXPECT_FALSE(dist.precompute(std::chrono::steady_clock::time_point::max()));
    EXPECT_FALSE(gone->done());
    EXPECT_EQ(gone->pins, 0);
    // No deadline: exact on the spot again.
    dist.set_deadline(RotationDist::Deadline::max());
    RotationDist::Table* u = dist.table(0);
    for (Vertex v = g.size() - 1; v >= 0; --v) ASSERT_EQ(dist.get(u, v, 1), brute(g, gd, v, 1, 0));
  }
}

TEST(Guidance, LoneRobotFollowsAGuidedShortestPath)
{
  // PIBT ranks by action cost + guided distance, so a lone robot's actions add up to the
  // guided distance of its start state (turns at the turn cost, forward at its arc's cost).
  int ran = 0;
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = random_grid(9, 7, 20, seed + 10);
    const Guidance gd = seed % 2 ? planner::arrow_guidance(g, 1, 4, 2) : random_guidance(g, seed, 5);
    planner::Rng rng(seed);
    for (int trial = 0; trial < 5; ++trial) {
      const Vertex s = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      const Vertex goal = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      const uint32_t want = brute(g, gd, s, 0, goal);
      if (want == RotationDist::kInf) continue;
      RotationPibt p(g, {s}, {goal}, seed);
      p.set_guidance(gd);
      uint32_t cost = 0;
      for (int steps = 0; !p.at_goal() && steps < 300; ++steps) {
        p.search(planner::Budget{});
        const char a = p.actions()[0];
        cost += a == 'F' ? gd.forward_cost(p.current()[0], p.headings()[0]) : a == 'W' ? 1000 : gd.turn;
        p.commit();
      }
      EXPECT_TRUE(p.at_goal());
      EXPECT_EQ(cost, want) << "seed " << seed << " from " << s << " to " << goal;
      ran += want > 2;
    }
  }
  EXPECT_GT(ran, 10);
}

TEST(Guidance, PibtRotWithArrowsMakesValidStepsAndRobotsArrive)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = random_grid(12, 10, 15, seed + 100);
    std::vector<int> comp = g.components();
    planner::Rng rng(seed);
    const std::vector<Vertex> cells = test::shuffled_cells(g, rng);
    const int n = 25;
    Config starts(cells.begin(), cells.begin() + n), goals(static_cast<size_t>(n));
    auto new_goal = [&](int i, Vertex from) { return goals[i] = test::random_goal(g, comp, rng, from); };
    for (int i = 0; i < n; ++i) new_goal(i, starts[i]);
    RotationPibt p(g, starts, goals, seed);
    p.set_guidance(planner::arrow_guidance(g, 2, 6, 2));
    if (seed >= 2) p.set_deadline(std::chrono::steady_clock::now());  // every query past it: lower bounds
    long arrivals = 0;
    for (int t = 1; t <= 300; ++t) {
      const Config cur = p.current();
      const std::vector<int> heads = p.headings();
      p.search(planner::Budget{});
      const Config next = p.next();
      ASSERT_EQ(planner::Validator::check_transition(g, cur, next), "") << "seed " << seed << " step " << t;
      const std::string acts = p.actions();
      for (size_t i = 0; i < cur.size(); ++i) {  // each action as LoRR applies it
        const Vertex want = acts[i] == 'F' ? p.dist().ahead(cur[i], heads[i]) : cur[i];
        ASSERT_GE(want, 0) << "forward into a wall";
        ASSERT_EQ(next[i], want) << "seed " << seed << " step " << t << " agent " << i << " " << acts[i];
      }
      p.commit();
      if (seed >= 2) p.precompute(std::chrono::steady_clock::time_point::max());  // the spare time catches up
      bool changed = false;
      for (int i = 0; i < n; ++i)
        if (p.current()[i] == goals[i]) ++arrivals, new_goal(i, goals[i]), changed = true;
      if (changed) p.set_goals(goals);
    }
    EXPECT_GT(arrivals, 50) << "seed " << seed;
  }
}
