// TrafficFlow (online traffic-flow guide paths): guide tables equal a brute-force
// Bellman-Ford over (cell, heading) under the same congestion costs, guide paths cost
// exactly their table value, flow counts kept incrementally equal a recount after any mix
// of plans, drops and advances, contraflow separates opposing flows; EPIBT ranking by them
// stays LoRR-valid in dense lifelong runs, and its guide-path work waits for a later step
// when a step's budget is spent.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "planner/rotation/epibt.hpp"
#include "planner/rotation/guidance.hpp"
#include "planner/rng.hpp"
#include "planner/rotation/rotation_dist.hpp"
#include "planner/rotation/traffic_flow.hpp"
#include "planner/validator.hpp"
#include "grid.hpp"

using planner::Config;
using planner::Graph;
using planner::RotationDist;
using planner::TrafficFlow;
using planner::Vertex;

namespace {

using test::random_grid;

// Random forward costs 1..4 per (cell, heading), turns 2: guide tables must use them.
planner::Guidance random_guidance(const Graph& g, uint64_t seed)
{
  planner::Rng rng(seed);
  planner::Guidance gd;
  gd.forward.resize(static_cast<size_t>(g.size()) * 4);
  for (auto& c : gd.forward) c = static_cast<uint16_t>(1 + rng.below(4));
  gd.turn = 2;
  return gd;
}

// Brute force: Bellman-Ford to a fixed point over (cell, heading), costs read from tf now.
std::vector<uint64_t> bellman_ford(const RotationDist& d, const TrafficFlow& tf, Vertex goal)
{
  const size_t n = static_cast<size_t>(d.graph().size()) * 4;
  const uint64_t inf = ~0ull;
  std::vector<uint64_t> h(n, inf);
  for (int o = 0; o < 4; ++o) h[static_cast<size_t>(goal) * 4 + static_cast<size_t>(o)] = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t s = 0; s < n; ++s) {
      const Vertex v = static_cast<Vertex>(s / 4);
      const int o = static_cast<int>(s % 4);
      if (v == goal) continue;
      uint64_t best = h[s];
      for (int t : {(o + 1) % 4, (o + 3) % 4})
        if (h[static_cast<size_t>(v) * 4 + static_cast<size_t>(t)] != inf) best = std::min(best, tf.turn() + h[static_cast<size_t>(v) * 4 + static_cast<size_t>(t)]);
      const Vertex u = d.ahead(v, o);
      if (u >= 0 && h[static_cast<size_t>(u) * 4 + static_cast<size_t>(o)] != inf)
        best = std::min(best, static_cast<uint64_t>(tf.forward(v, o)) + h[static_cast<size_t>(u) * 4 + static_cast<size_t>(o)]);
      if (best < h[s]) h[s] = best, changed = true;
    }
  }
  return h;
}

// Flow counts recounted from every robot's guide path still ahead.
void expect_counts_match(const RotationDist& d, const TrafficFlow& tf, int agents)
{
  const size_t n = static_cast<size_t>(d.graph().size());
  std::vector<uint32_t> flow(n * 4, 0), load(n, 0);
  for (int i = 0; i < agents; ++i)
    for (int32_t s : tf.path(i)) ++flow[static_cast<size_t>(s)], ++load[static_cast<size_t>(d.ahead(s / 4, s % 4))];
  for (Vertex v = 0; v < static_cast<Vertex>(n); ++v) {
    ASSERT_EQ(tf.load(v), load[static_cast<size_t>(v)]) << "cell " << v;
    for (int o = 0; o < 4; ++o) ASSERT_EQ(tf.flow(v, o), flow[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)]) << "cell " << v << " heading " << o;
  }
}

}  // namespace

TEST(TrafficFlow, GuideTablesEqualBruteForceUnderTheSameCongestionCosts)
{
  for (uint64_t seed = 0; seed < 3; ++seed) {
    const Graph g = random_grid(9, 7, 15, seed + 40);
    RotationDist d(g);
    d.set_guidance(random_guidance(g, seed));
    planner::TrafficFlowOptions opt;
    opt.contraflow = 1.5, opt.vertex = 0.5;
    const int agents = 12;
    TrafficFlow tf(d, static_cast<size_t>(agents), opt);
    planner::Rng rng(seed);
    const std::vector<int> comp = g.components();
    int compared = 0;
    for (int round = 0; round < 3; ++round)
      for (int i = 0; i < agents; ++i) {
        const Vertex v = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
        Vertex goal;
        do goal = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
        while (comp[goal] != comp[v]);
        const int o = static_cast<int>(rng.below(4));
        tf.drop(i);  // plan() removes the robot's own path first: the costs it plans under
        const std::vector<uint64_t> want = bellman_ford(d, tf, goal);
        std::vector<uint32_t> fwd(static_cast<size_t>(g.size()) * 4);  // the costs before its path is added
        for (Vertex u = 0; u < g.size(); ++u)
          for (int k = 0; k < 4; ++k) fwd[static_cast<size_t>(u) * 4 + static_cast<size_t>(k)] = tf.forward(u, k);
        tf.plan(i, v, o, goal);
        ASSERT_TRUE(tf.has(i));
        for (Vertex u = 0; u < g.size(); ++u)
          for (int k = 0; k < 4; ++k) {
            const uint64_t w = want[static_cast<size_t>(u) * 4 + static_cast<size_t>(k)];
            ASSERT_EQ(tf.h(i, u, k), w == ~0ull ? TrafficFlow::kInf : w) << "seed " << seed << " cell " << u << " heading " << k;
          }
        // Its guide path: adjacent forward moves from its state to the goal, costing h exactly.
        const std::vector<int32_t> p = tf.path(i);
        Vertex at = v;
        int hd = o;
        uint64_t cost = 0;
        for (int32_t s : p) {
          ASSERT_EQ(s / 4, at);
          const int turns = std::min((s % 4 - hd + 4) % 4, (hd - s % 4 + 4) % 4);
          cost += static_cast<uint64_t>(turns) * tf.turn() + fwd[static_cast<size_t>(s)];
          at = d.ahead(at, s % 4), hd = s % 4;
          ASSERT_GE(at, 0);
        }
        EXPECT_EQ(at, goal);
        EXPECT_EQ(cost, want[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)]) << "seed " << seed << " agent " << i;
        ++compared;
      }
    EXPECT_EQ(compared, 3 * agents);
    EXPECT_GT(tf.plans(), 0u);
  }
}

TEST(TrafficFlow, FlowCountsEqualARecountAfterPlansDropsAndAdvances)
{
  const Graph g = random_grid(12, 10, 10, 5);
  RotationDist d(g);
  const int agents = 20;
  TrafficFlow tf(d, static_cast<size_t>(agents), {});
  planner::Rng rng(1);
  const std::vector<int> comp = g.components();
  uint32_t total = 0;
  for (int k = 0; k < 400; ++k) {
    const int i = static_cast<int>(rng.below(agents));
    const uint32_t what = rng.below(4);
    if (what == 0) {
      tf.drop(i);
    } else if (what == 1 && !tf.path(i).empty()) {  // the robot makes its next guided move
      const int32_t s = tf.path(i).front();
      tf.advance(i, s / 4, s % 4);
    } else if (what == 2) {
      tf.advance(i, static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size()))), static_cast<int>(rng.below(4)));  // off its guide: no change
    } else {
      const Vertex v = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      Vertex goal;
      do goal = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      while (comp[goal] != comp[v]);
      tf.plan(i, v, static_cast<int>(rng.below(4)), goal);
    }
    expect_counts_match(d, tf, agents);
    if (HasFatalFailure()) return;
    for (Vertex v = 0; v < g.size(); ++v) total += tf.load(v);
  }
  EXPECT_GT(total, 0u);  // the counts were not trivially empty
}

TEST(TrafficFlow, ContraflowSendsAnOpposingRobotToTheOtherLane)
{
  // Two lanes; three robots planned east along the top one. A robot going west from the
  // top lane's east end takes the top lane without congestion costs, the bottom one with.
  const Graph g = test::grid({".......", "......."});
  RotationDist d(g);
  for (double contraflow : {0.0, 2.0}) {
    planner::TrafficFlowOptions opt;
    opt.contraflow = contraflow, opt.vertex = 0;
    TrafficFlow tf(d, 4, opt);
    for (int i = 0; i < 3; ++i) tf.plan(i, g.at(0, 0), 0, g.at(6, 0));
    EXPECT_EQ(tf.flow(g.at(2, 0), 0), 3u);
    tf.plan(3, g.at(6, 0), 2, g.at(0, 0));
    int bottom = 0;
    for (int32_t s : tf.path(3)) bottom += g.cell_y(s / 4) == 1;
    if (contraflow == 0) EXPECT_EQ(bottom, 0);
    else EXPECT_GE(bottom, 5);
  }
}

TEST(TrafficFlow, BadWeightsAreRefused)
{
  const Graph g = test::grid({"..."});
  RotationDist d(g);
  planner::TrafficFlowOptions bad;
  bad.contraflow = -1;
  EXPECT_THROW(TrafficFlow(d, 1, bad), std::invalid_argument);
  bad = {}, bad.vertex = 2000;
  EXPECT_THROW(TrafficFlow(d, 1, bad), std::invalid_argument);
  bad = {}, bad.refresh = -1;
  EXPECT_THROW(TrafficFlow(d, 1, bad), std::invalid_argument);
  bad = {}, bad.share = 0;
  EXPECT_THROW(TrafficFlow(d, 1, bad), std::invalid_argument);
}

TEST(TrafficFlow, EpibtWithGuidePathsStaysValidInDenseLifelongRuns)
{
  // 30 robots on a 12 x 10 grid (about 30 % of the free cells), new goals on arrival,
  // 300 steps; guided (arrows) and not, with and without refreshes.
  for (int variant = 0; variant < 3; ++variant)
    for (uint64_t seed = 0; seed < 2; ++seed) {
      const Graph g = random_grid(12, 10, 15, seed + 100);
      const std::vector<int> comp = g.components();
      planner::Rng rng(seed);
      const std::vector<Vertex> cells = test::shuffled_cells(g, rng);
      const int n = 30;
      Config starts(cells.begin(), cells.begin() + n), goals(static_cast<size_t>(n));
      auto new_goal = [&](int i, Vertex from) { return goals[i] = test::random_goal(g, comp, rng, from); };
      for (int i = 0; i < n; ++i) new_goal(i, starts[i]);
      planner::EpibtOptions opt;
      opt.seed = seed;
      opt.tf.on = true;
      opt.tf.refresh = variant == 2 ? 3 : 0;
      planner::Epibt p(g, starts, goals, opt);
      if (variant >= 1) p.set_guidance(planner::arrow_guidance(g, 1, 3, 1));
      ASSERT_NE(p.traffic_flow(), nullptr);
      long arrivals = 0;
      for (int t = 1; t <= 300; ++t) {
        const Config cur = p.current();
        p.search(planner::Budget{});
        EXPECT_EQ(p.tf_pending(), 0u);  // no deadline: every wanted guide table is computed
        const Config next = p.next();
        ASSERT_EQ(planner::Validator::check_transition(g, cur, next), "") << "variant " << variant << " seed " << seed << " step " << t;
        const std::string acts = p.actions();
        for (int i = 0; i < n; ++i) {
          ASSERT_TRUE(p.traffic_flow()->has(i));
          ASSERT_EQ(acts[i] == 'F', next[i] != cur[i]) << "agent " << i << " step " << t;
        }
        p.commit();
        for (int i = 0; i < n; ++i)
          if (p.current()[i] == goals[i]) ++arrivals, new_goal(i, goals[i]);
        p.set_goals(goals);
      }
      expect_counts_match(p.dist(), *p.traffic_flow(), n);
      EXPECT_GT(arrivals, 50) << "variant " << variant << " seed " << seed;
      EXPECT_GE(p.traffic_flow()->plans(), static_cast<uint64_t>(arrivals));  // a plan per goal change
    }
}

TEST(TrafficFlow, GuideWorkPastTheBudgetWaitsAndTheStepStaysValid)
{
  const Graph g = random_grid(16, 16, 10, 7);
  planner::Rng rng(3);
  const std::vector<Vertex> cells = test::shuffled_cells(g, rng);
  const Config starts(cells.begin(), cells.begin() + 60), goals(cells.begin() + 60, cells.begin() + 120);
  planner::EpibtOptions opt;
  opt.tf.on = true;
  planner::Epibt p(g, starts, goals, opt);
  EXPECT_EQ(p.tf_pending(), 60u);
  const Config cur = p.current();
  p.search(planner::Budget::time_ms(0));  // no time: no guide table yet, robots rank by the shared tables
  EXPECT_EQ(p.tf_pending(), 60u);
  ASSERT_EQ(planner::Validator::check_transition(g, cur, p.next()), "");
  p.commit();
  EXPECT_FALSE(p.precompute(planner::Clock::time_point::max()));  // spare time: all of them
  EXPECT_EQ(p.tf_pending(), 0u);
  for (int i = 0; i < 60; ++i) EXPECT_TRUE(p.traffic_flow()->has(i));
  // Off where the tables would not fit.
  opt.tf.max_entries = 60 * 4 * static_cast<size_t>(g.size()) - 1;
  planner::Epibt q(g, starts, goals, opt);
  EXPECT_EQ(q.traffic_flow(), nullptr);
  EXPECT_EQ(q.tf_pending(), 0u);
}
