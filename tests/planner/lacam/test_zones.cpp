// One-at-a-time zones as a rule of PIBT's configurations (planner/zones.hpp): checked by
// exhaustive search on tiny random graphs with a zone, LaCAM solves exactly the instances a
// BFS over joint configurations that keep the zone solves, RT-LaCAM reaches the goal on all
// of them, and no step of either puts two agents in the zone (the rule counts an agent in it
// before or after the step). The BFS and the zone check are the test's own.
#include <gtest/gtest.h>

#include <iostream>
#include <queue>
#include <random>
#include <set>

#include "planner/dist_table.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/lacam/pibt_planner.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/validator.hpp"
#include "planner/zones.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

// The test's own rule: per step, at most one agent in the zone before or after it.
bool keeps_zone(const std::set<Vertex>& zone, const Config& from, const Config& to)
{
  int inside = 0;
  for (size_t i = 0; i < from.size(); ++i) inside += zone.count(from[i]) || zone.count(to[i]);
  return inside <= 1;
}

bool joint_bfs_solvable(const Graph& g, const std::set<Vertex>& zone, const Config& starts, const Config& goals)
{
  return test::joint_bfs_solvable(
      starts, goals, [&](Vertex v) { auto nb = g.neighbors(v); return std::vector<Vertex>(nb.begin(), nb.end()); },
      [&](const Config& from, const Config& to) { return keeps_zone(zone, from, to); });
}

// A connected random graph on n vertices (a random spanning tree plus a few edges).
Graph random_connected(std::mt19937& rng, int n)
{
  std::vector<std::pair<Vertex, Vertex>> arcs;
  for (Vertex v = 1; v < n; ++v) {
    const Vertex u = static_cast<Vertex>(rng() % v);
    arcs.push_back({u, v}), arcs.push_back({v, u});
  }
  for (int e = 0; e < n / 2; ++e) {
    const Vertex u = rng() % n, v = rng() % n;
    if (u != v) arcs.push_back({u, v}), arcs.push_back({v, u});
  }
  std::sort(arcs.begin(), arcs.end());
  arcs.erase(std::unique(arcs.begin(), arcs.end()), arcs.end());
  return Graph::from_arcs(n, arcs);
}

}  // namespace

TEST(Zones, ZoneConflictNamesTheZoneAndTheAgents)
{
  auto z = Zones::from_cells(6, {{1, 2}, {4}});
  EXPECT_EQ(zone_conflict(*z, {0, 3}, {1, 3}), "");
  EXPECT_EQ(zone_conflict(*z, {1, 3}, {0, 2}), "zone 0: agents 0 and 1");  // one leaves as one enters
  EXPECT_EQ(zone_conflict(*z, {1, 4}, {2, 3}), "");                         // two zones, one each
}

// The exhaustive check: random connected graphs on 5-7 vertices, a zone of 2-3 vertices, 2 or 3
// agents, sampled start/goal pairs with at most one agent of each in the zone.
TEST(Zones, LacamAndRtLacamAgreeWithAJointBfsThatKeepsTheZone)
{
  std::mt19937 rng(35);
  int solvable = 0, unsolvable = 0, broken_without = 0;
  for (int gi = 0; gi < 30; ++gi) {
    const int n = 5 + gi % 3, k = 2 + gi % 2;
    const Graph g = random_connected(rng, n);
    std::vector<Vertex> perm(n);
    for (int v = 0; v < n; ++v) perm[v] = v;
    std::shuffle(perm.begin(), perm.end(), rng);
    const std::vector<Vertex> cells(perm.begin(), perm.begin() + 2 + gi % 2);
    const std::set<Vertex> zone(cells.begin(), cells.end());
    LacamOptions zoned;
    zoned.zones = Zones::from_cells(n, {cells});
    for (int c = 0; c < 10; ++c) {
      Config s, goal;
      for (Config* x : {&s, &goal}) {
        std::shuffle(perm.begin(), perm.end(), rng);
        x->assign(perm.begin(), perm.begin() + k);
      }
      if (!keeps_zone(zone, s, s) || !keeps_zone(zone, goal, goal)) continue;  // two in the zone at rest
      const bool expect = joint_bfs_solvable(g, zone, s, goal);
      (expect ? solvable : unsolvable)++;
      SCOPED_TRACE("graph " + std::to_string(gi) + (expect ? " solvable" : " unsolvable"));
      for (bool refine : {false, true}) {
        LacamOptions o = zoned;
        o.refine = refine;
        DistTable d(g);
        Lacam l(g, d, o);
        l.reset(s, goal);
        ASSERT_EQ(l.search(Budget::unlimited()) == Status::Solved, expect) << "LaCAM (refine " << refine << ")";
        if (!expect) continue;
        const std::vector<Config> plan = l.path(l.goal_node());
        Validator val(g, s, goal);
        for (size_t t = 1; t < plan.size(); ++t) {
          ASSERT_TRUE(keeps_zone(zone, plan[t - 1], plan[t])) << "step " << t;
          ASSERT_TRUE(val.step(plan[t])) << val.error();
        }
      }
      if (!expect) continue;
      for (bool refine : {false, true}) {
        LacamOptions o = zoned;
        o.refine = refine;
        RtLacam rt(g, s, goal, o);
        Validator val(g, s, goal);
        Config prev = s;
        for (long step = 0; !rt.at_goal(); ++step) {
          ASSERT_LT(step, 20000) << "RT-LaCAM makes no progress";
          rt.step(Budget::expansion_count(1));
          rt.commit();
          ASSERT_TRUE(keeps_zone(zone, prev, rt.current())) << "RT-LaCAM (refine " << refine << ") step " << step;
          ASSERT_TRUE(val.step(rt.current())) << val.error();
          prev = rt.current();
        }
      }
      // Without the rule LaCAM's plan breaks the zone on some instances (the rule does something).
      DistTable d(g);
      Lacam plain(g, d);
      plain.reset(s, goal);
      if (plain.search(Budget::unlimited()) == Status::Solved) {
        const std::vector<Config> plan = plain.path(plain.goal_node());
        for (size_t t = 1; t < plan.size(); ++t)
          if (!keeps_zone(zone, plan[t - 1], plan[t])) {
            ++broken_without;
            break;
          }
      }
    }
  }
  std::cout << "[ info ] " << solvable << " solvable, " << unsolvable << " unsolvable with the zone; "
            << broken_without << " plans without the rule break it\n";
  EXPECT_GT(solvable, 50);
  EXPECT_GT(unsolvable, 3);
  EXPECT_GT(broken_without, 10);
}

// A crowded grid with a zone across its middle column: PIBT alone (no search) never plans a
// step that puts two agents in it, over many random steps.
TEST(Zones, PibtNeverPlansTwoAgentsIntoAZone)
{
  const Graph g = test::grid({".......", ".......", ".......", ".......", "......."});
  std::vector<Vertex> cells;
  for (int y = 0; y < 5; ++y) cells.push_back(g.at(3, y));
  LacamOptions o;
  o.zones = Zones::from_cells(g.size(), {cells});
  std::mt19937 rng(7);
  int entries = 0;
  for (int run = 0; run < 20; ++run) {
    std::vector<Vertex> free;
    for (Vertex v = 0; v < g.size(); ++v)
      if (g.cell_x(v) != 3) free.push_back(v);
    std::shuffle(free.begin(), free.end(), rng);
    const Config s(free.begin(), free.begin() + 10);
    std::shuffle(free.begin(), free.end(), rng);
    const Config goal(free.begin(), free.begin() + 10);
    o.seed = run;
    PibtPlanner p(g, s, goal, o);
    Config prev = s;
    for (int t = 0; t < 60 && !p.at_goal(); ++t) {
      p.step(Budget::unlimited());
      p.commit();
      ASSERT_EQ(zone_conflict(*o.zones, prev, p.current()), "") << "run " << run << " step " << t;
      for (size_t i = 0; i < prev.size(); ++i) entries += !o.zones->of[p.current()[i]].empty() && o.zones->of[prev[i]].empty();
      prev = p.current();
    }
  }
  EXPECT_GT(entries, 20);  // agents did cross the zone
}

// Priority inheritance for a zone (Pibt::evict): an agent standing in a zone that a higher
// agent asks to enter leaves it by the way out farthest from the asker. The ranking was a
// float offset, 1e20f + exit distance, which rounds every exit distance away: the evicted
// agent took its moves in neighbour order, and in one of the two directions below it stepped
// toward the asker and back for ever (small_rules_lifelong, fleet seed 4: an errand stalled
// 600 ticks at the zone's mouth). A one-wide corridor, the zone its cells 3-5, the holder
// parked on its goal in the middle, the asker beside the zone bound for the far end.
TEST(Zones, AnEvictedAgentLeavesByTheWayOutAwayFromTheAsker)
{
  const Graph g = test::grid({"........."});
  LacamOptions o;
  o.zones = Zones::from_cells(g.size(), {{g.at(3, 0), g.at(4, 0), g.at(5, 0)}});
  for (const bool east : {true, false}) {
    const int from = east ? 2 : 6, to = east ? 8 : 0, away = east ? 5 : 3;
    const Config s{g.at(from, 0), g.at(4, 0)}, goal{g.at(to, 0), g.at(4, 0)};
    PibtPlanner p(g, s, goal, o);
    p.set_priority_hint({100.0f, 0.0f});  // the asker moves first
    p.set_goals(goal);
    p.search(Budget::unlimited());
    p.commit();
    EXPECT_EQ(p.current()[1], g.at(away, 0)) << (east ? "east" : "west") << ": the holder stepped toward the asker";
    int entered = -1;  // the step the asker is in the zone
    for (int t = 1; t <= 10 && entered < 0; ++t) {
      p.search(Budget::unlimited());
      p.commit();
      if (!o.zones->of[p.current()[0]].empty()) entered = t;
    }
    EXPECT_GE(entered, 0) << (east ? "east" : "west") << ": the asker never got into the zone";
    EXPECT_LE(entered, 3) << (east ? "east" : "west");
  }
}
