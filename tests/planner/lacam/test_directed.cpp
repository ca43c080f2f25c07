// Directed graphs (one-way arcs): the graph keeps arc directions, distances run backwards
// from the goal, and, checked by exhaustive search on tiny random directed instances, LaCAM
// solves exactly the instances a BFS over joint configurations solves, RT-LaCAM (with its
// one-way rule, rt_lacam.hpp) reaches the goal on all of them, and every executed move
// follows an arc. The BFS and the arc checks use the test's own arc list, not Graph, so a
// graph that forgot directions fails here.
#include <gtest/gtest.h>

#include <iostream>
#include <map>
#include <queue>
#include <random>
#include <set>

#include "planner/dist_table.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/one_way_aisles.hpp"
#include "planner/error.hpp"
#include "planner/validator.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

using Arcs = std::vector<std::pair<Vertex, Vertex>>;

struct Tiny {
  int n = 0;
  Arcs arcs;
  std::set<std::pair<Vertex, Vertex>> has;  // the arcs, for move checks
};

// n vertices; each pair is absent, two-way, or one-way either way. At least one one-way arc.
Tiny random_tiny(std::mt19937& rng, int n)
{
  for (;;) {
    Tiny t;
    t.n = n;
    int one_way = 0;
    for (Vertex u = 0; u < n; ++u)
      for (Vertex v = u + 1; v < n; ++v) {
        switch (rng() % 5) {
          case 0: case 1: break;
          case 2: t.arcs.push_back({u, v}), t.arcs.push_back({v, u}); break;
          case 3: t.arcs.push_back({u, v}), ++one_way; break;
          default: t.arcs.push_back({v, u}), ++one_way; break;
        }
      }
    if (one_way == 0) continue;
    t.has.insert(t.arcs.begin(), t.arcs.end());
    return t;
  }
}

// Whether `goals` is reachable from `starts` by joint moves along the test's own arcs.
bool joint_bfs_solvable(const Tiny& t, const Config& starts, const Config& goals)
{
  std::vector<std::vector<Vertex>> out(t.n);
  for (auto [u, v] : t.arcs) out[u].push_back(v);
  return test::joint_bfs_solvable(starts, goals, [&](Vertex v) { return out[v]; });
}

bool single_reachable(const Tiny& t, Vertex s, Vertex g)
{
  std::set<Vertex> seen{s};
  std::vector<Vertex> todo{s};
  while (!todo.empty()) {
    Vertex v = todo.back();
    todo.pop_back();
    for (auto [a, b] : t.arcs)
      if (a == v && seen.insert(b).second) todo.push_back(b);
  }
  return seen.count(g) > 0;
}

// Every agent waits or follows one of the test's own arcs.
std::string check_moves(const Tiny& t, const Config& from, const Config& to)
{
  for (size_t i = 0; i < from.size(); ++i)
    if (from[i] != to[i] && !t.has.count({from[i], to[i]}))
      return "agent " + std::to_string(i) + " moves " + std::to_string(from[i]) + " -> " + std::to_string(to[i]) +
             " against the arcs";
  return "";
}

// Random start/goal configurations of k agents on t.n vertices (distinct vertices each).
std::vector<std::pair<Config, Config>> sample_instances(std::mt19937& rng, int n, int k, int count)
{
  std::vector<std::pair<Config, Config>> out;
  std::vector<Vertex> perm(n);
  for (int c = 0; c < count; ++c) {
    std::pair<Config, Config> p;
    for (Config* x : {&p.first, &p.second}) {
      for (int v = 0; v < n; ++v) perm[v] = v;
      std::shuffle(perm.begin(), perm.end(), rng);
      x->assign(perm.begin(), perm.begin() + k);
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

TEST(DirectedGraph, KeepsArcDirectionsAndReversesDistances)
{
  // A one-way ring 0 -> 1 -> 2 -> 3 -> 0 with a two-way spur 3 <-> 4.
  Graph g = Graph::from_arcs(5, {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {3, 4}, {4, 3}});
  EXPECT_TRUE(g.directed());
  EXPECT_EQ(g.num_one_way(), 4u);
  EXPECT_TRUE(g.adjacent(0, 1));
  EXPECT_FALSE(g.adjacent(1, 0));
  EXPECT_EQ(g.in_neighbors(0).size(), 1u);
  EXPECT_EQ(g.in_neighbors(0)[0], 3);
  int count = 0;
  g.strong_components(&count);
  EXPECT_EQ(count, 1);
  EXPECT_FALSE(Graph::from_arcs(3, {{0, 1}, {1, 2}}).reaches(2, 0));
  Graph::from_arcs(3, {{0, 1}, {1, 2}}).strong_components(&count);
  EXPECT_EQ(count, 3);
  // Distances to goal 0 follow the arcs: 1 is three moves away, 3 one move.
  DistTable d(g);
  d.set_goals({0});
  EXPECT_EQ(d.get(0, 1), 3);
  EXPECT_EQ(d.get(0, 3), 1);
  EXPECT_EQ(d.get(0, 4), 2);
  // Both arcs of every pair: the same graph as from_edges, undirected.
  EXPECT_FALSE(Graph::from_arcs(2, {{0, 1}, {1, 0}}).directed());
}

TEST(DirectedGraph, ValidatorRejectsAMoveAgainstAnArc)
{
  Graph g = Graph::from_arcs(3, {{0, 1}, {1, 2}, {2, 0}});
  EXPECT_EQ(Validator::check_transition(g, {0}, {1}), "");
  EXPECT_NE(Validator::check_transition(g, {1}, {0}), "");
}

TEST(DirectedGraph, UnreachableGoalIsAnErrorNotASearch)
{
  Graph g = Graph::from_arcs(3, {{0, 1}, {1, 2}});
  DistTable d(g);
  Lacam l(g, d);
  try {
    l.reset({2}, {0});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("agent 0: goal 0 is unreachable from start 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RtLacam(g, {2}, {0}), std::invalid_argument);
  Instance ins;
  ins.starts = {2};
  ins.goals = {0};
  EXPECT_THROW(ins.check(g), InputError);
}

// The exhaustive check. Random directed graphs on 4-6 vertices, 2 or 3 agents, sampled
// start/goal pairs (every one whose goals are reachable agent by agent along the arcs).
TEST(DirectedGraph, LacamAndRtLacamAgreeWithJointBfs)
{
  std::mt19937 rng(24);
  int solvable = 0, unsolvable = 0, one_way_moves = 0;
  for (int gi = 0; gi < 36; ++gi) {
    const int n = 4 + gi % 3, k = 2 + gi % 2;
    const Tiny t = random_tiny(rng, n);
    const Graph g = Graph::from_arcs(n, t.arcs);
    for (const auto& [s, goal] : sample_instances(rng, n, k, 12)) {
      bool reachable = true;
      for (int i = 0; i < k; ++i) reachable = reachable && single_reachable(t, s[i], goal[i]);
      if (!reachable) continue;  // refused up front (UnreachableGoalIsAnErrorNotASearch)
      const bool expect = joint_bfs_solvable(t, s, goal);
      (expect ? solvable : unsolvable)++;
      SCOPED_TRACE("graph " + std::to_string(gi) + (expect ? " solvable" : " unsolvable"));
      for (bool refine : {false, true}) {
        LacamOptions o;
        o.refine = refine;
        DistTable d(g);
        Lacam l(g, d, o);
        l.reset(s, goal);
        const Status st = l.search(Budget::unlimited());
        ASSERT_EQ(st == Status::Solved, expect) << "LaCAM (refine " << refine << ") disagrees with the joint BFS";
        if (!expect) continue;
        const std::vector<Config> plan = l.path(l.goal_node());
        Validator val(g, s, goal);
        for (size_t k2 = 1; k2 < plan.size(); ++k2) {
          ASSERT_EQ(check_moves(t, plan[k2 - 1], plan[k2]), "");
          ASSERT_TRUE(val.step(plan[k2])) << val.error();
        }
        ASSERT_EQ(plan.back(), goal);
      }
      // RT-LaCAM, one expansion per step, with and without RT-LaCAM*.
      for (bool refine : {false, true}) {
        LacamOptions o;
        o.refine = refine;
        RtLacam rt(g, s, goal, o);
        Validator val(g, s, goal);
        Config prev = s;
        long long step = 0;
        for (; !rt.at_goal() && !rt.exhausted(); ++step) {
          ASSERT_LT(step, 20000) << "RT-LaCAM makes no progress";
          rt.step(Budget::expansion_count(1));
          rt.commit();
          ASSERT_EQ(check_moves(t, prev, rt.current()), "") << "step " << step;
          ASSERT_TRUE(val.step(rt.current())) << val.error();
          for (int i = 0; i < k; ++i) one_way_moves += prev[i] != rt.current()[i] && !g.adjacent(rt.current()[i], prev[i]);
          prev = rt.current();
        }
        ASSERT_EQ(rt.at_goal(), expect) << "RT-LaCAM (refine " << refine << ")";
      }
    }
  }
  std::cout << "[ info ] " << solvable << " solvable, " << unsolvable << " unsolvable instances; " << one_way_moves
            << " RT-LaCAM moves along one-way arcs\n";
  // The sample must exercise both outcomes and moves along one-way arcs.
  EXPECT_GT(solvable, 50);
  EXPECT_GT(unsolvable, 5);
  EXPECT_GT(one_way_moves, 50);
}

// A miniature warehouse with one-way aisles (one_way_aisles.hpp), crowded: RT-LaCAM with
// its default PIBT (swap on) and RT-LaCAM* reach the goals, every move along an arc. PIBT's
// swap pulls an agent into the vertex the pusher leaves; over a one-way arc that pull does
// not exist (the bug this test caught: an agent moving west on an east-only aisle).
TEST(DirectedGraph, CrowdedOneWayWarehouseRunsValid)
{
  const Graph grid = test::grid({"...........",
                                 "...........",
                                 "..@@@.@@@..",
                                 "...........",
                                 "..@@@.@@@..",
                                 "...........",
                                 "..@@@.@@@..",
                                 "...........",
                                 "..........."});
  const Graph g = one_way_aisles(grid);
  ASSERT_TRUE(g.directed());
  // Rows 1, 3, 5, 7 run along shelves: east, west, east, west; row 0 and the gaps two-way.
  EXPECT_TRUE(g.adjacent(g.at(3, 1), g.at(4, 1)));
  EXPECT_FALSE(g.adjacent(g.at(4, 1), g.at(3, 1)));
  EXPECT_TRUE(g.adjacent(g.at(4, 3), g.at(3, 3)));
  EXPECT_FALSE(g.adjacent(g.at(3, 3), g.at(4, 3)));
  EXPECT_TRUE(g.adjacent(g.at(3, 0), g.at(4, 0)) && g.adjacent(g.at(4, 0), g.at(3, 0)));
  std::mt19937 rng(7);
  uint64_t expansions = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const auto inst = sample_instances(rng, g.size(), 30, 1).front();
    for (bool refine : {false, true}) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " refine " + std::to_string(refine));
      LacamOptions o;
      o.refine = refine;
      o.seed = static_cast<uint64_t>(trial);
      RtLacam rt(g, inst.first, inst.second, o);
      Validator val(g, inst.first, inst.second);
      for (long long step = 0; !rt.at_goal(); ++step) {
        ASSERT_LT(step, 3000) << "RT-LaCAM makes no progress";
        rt.step(Budget::expansion_count(20));
        rt.commit();
        ASSERT_TRUE(val.step(rt.current())) << val.error();
      }
      expansions += rt.expansions();
    }
  }
  EXPECT_GT(expansions, 24u);  // searched, not solved by the first PIBT step everywhere
}

namespace {

struct OneWayRun {
  long long makespan = 0, soc = 0;
  uint64_t lookaheads = 0, switches = 0;
};

// RT-LaCAM* (refine) at `expansions` per iteration to the goal, every move checked.
OneWayRun one_way_run(const Graph& g, const Instance& ins, uint64_t expansions, bool lookahead)
{
  LacamOptions o;
  o.refine = true;
  o.lookahead = lookahead;
  RtLacam rt(g, ins.starts, ins.goals, o);
  Validator val(g, ins.starts, ins.goals);
  OneWayRun r;
  for (long long step = 0; !rt.at_goal(); ++step) {
    if (step >= 20000) {
      ADD_FAILURE() << "no goal in 20000 steps";
      return r;
    }
    rt.step(Budget::expansion_count(expansions));
    rt.commit();
    if (!val.step(rt.current())) {
      ADD_FAILURE() << val.error();
      return r;
    }
    r.makespan = step + 1;
  }
  r.soc = val.sum_of_costs();
  r.lookaheads = rt.lookaheads(), r.switches = rt.switches();
  return r;
}

}  // namespace

// RT-LaCAM*'s lookahead (rt_lacam.hpp): on one-way aisles the first one-way move along the
// goal's path ends refinement, and LaCAM's first solution can be long. warehouse-10-20-10-2-1
// with one-way aisles, scen 2, N = 200, 50 expansions per iteration (the library's options:
// LaCAM* with its defaults): measured makespan 211 and standard SOC 24746 with the lookahead,
// 400 and 26517 without. Both runs valid and solved: the lookahead only ever takes over a
// strictly shorter path. Off, it never starts.
TEST(DirectedGraph, LookaheadShortensALongFirstPathOnOneWayAisles)
{
  const Graph g = one_way_aisles(load_map(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1.map"));
  ASSERT_TRUE(g.directed());
  const Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/warehouse-10-20-10-2-1-random-2-first200.scen", g, 200);
  const OneWayRun on = one_way_run(g, ins, 50, true);
  const OneWayRun off = one_way_run(g, ins, 50, false);
  std::printf("makespan %lld / %lld, SOC %lld / %lld, lookaheads %llu, switches %llu\n", on.makespan, off.makespan,
              on.soc, off.soc, static_cast<unsigned long long>(on.lookaheads), static_cast<unsigned long long>(on.switches));
  EXPECT_GT(on.switches, 0u);
  EXPECT_EQ(off.lookaheads, 0u);
  EXPECT_LT(on.makespan * 10, off.makespan * 7);  // under 0.7x
  EXPECT_LT(on.soc, off.soc);
}
