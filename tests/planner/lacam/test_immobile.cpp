// Immobile agents (planner/immobile.hpp): a stuck agent is never moved, the others route
// around it, and clearing the mark restores completeness.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <random>

#include "planner/dist_table.hpp"
#include "planner/lacam/immobile.hpp"
#include "planner/lacam/pibt.hpp"
#include "planner/lacam/priority.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/solver.hpp"
#include "planner/validator.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

// Steps the planner (search, next, commit) until `done` or `max_steps`; every configuration
// is validated; with `fixed` >= 0, that agent must stay on `where` in every one.
struct Drive {
  std::vector<Config> plan;
  std::string error;
};

template <class Done>
Drive drive(RealtimePlanner& p, const Graph& g, int max_steps, int fixed, Vertex where, Done done)
{
  Drive d;
  d.plan.push_back(p.current());
  for (int s = 0; s < max_steps && !done(); ++s) {
    p.search(Budget::expansion_count(20));
    const Config next = p.next();
    p.commit();
    const std::string e = Validator::check_transition(g, d.plan.back(), next);
    if (!e.empty() && d.error.empty()) d.error = "step " + std::to_string(s) + ": " + e;
    if (fixed >= 0 && next[fixed] != where && d.error.empty()) d.error = "step " + std::to_string(s) + ": immobile agent moved";
    d.plan.push_back(next);
  }
  return d;
}

// A two-lane corridor; agent 0 (X) is stuck in the top lane where A and B want to pass.
struct Corridor {
  Graph g = test::grid({"........", "........"});
  Config starts = test::at(g, {{3, 0}, {0, 0}, {7, 0}, {0, 1}, {7, 1}});
  Config goals = test::at(g, {{5, 1}, {7, 0}, {0, 0}, {7, 1}, {0, 1}});
};

}  // namespace

TEST(Immobile, OthersPassAroundAnImmobileAgentInATwoLaneCorridorThenAllFinish)
{
  Corridor c;
  for (bool refine : {false, true})
    for (uint64_t seed = 0; seed < 5; ++seed) {
      SCOPED_TRACE("refine " + std::to_string(refine) + " seed " + std::to_string(seed));
      SolverOptions o;
      o.seed = seed;
      o.lacam.refine = refine;
      auto p = make_planner(Solver::RtLacam, c.g, c.starts, c.goals, o);
      p->set_immobile(0, true);
      // The others reach their goals around X, which never moves.
      auto others_home = [&] {
        for (size_t i = 1; i < c.goals.size(); ++i)
          if (p->current()[i] != c.goals[i]) return false;
        return true;
      };
      Drive d = drive(*p, c.g, 500, 0, c.starts[0], others_home);
      EXPECT_EQ(d.error, "");
      EXPECT_TRUE(others_home());
      EXPECT_FALSE(p->at_goal());  // the real goal test still needs X on its goal
      EXPECT_FALSE(p->exhausted());
      // Staying there: more steps keep everybody put (the relaxed goal is reached).
      Drive rest = drive(*p, c.g, 10, 0, c.starts[0], [] { return false; });
      EXPECT_EQ(rest.error, "");
      EXPECT_EQ(rest.plan.back(), d.plan.back());
      // X frees: completeness again, all reach their goals.
      p->set_immobile(0, false);
      Drive after = drive(*p, c.g, 500, -1, -1, [&] { return p->at_goal(); });
      EXPECT_EQ(after.error, "");
      EXPECT_TRUE(p->at_goal());
      EXPECT_EQ(p->current(), c.goals);
    }
}

TEST(Immobile, NaiveAndPibtNeverMoveTheImmobileAgent)
{
  Corridor c;
  for (Solver s : {Solver::Naive, Solver::Pibt}) {
    SCOPED_TRACE(to_string(s));
    auto p = make_planner(s, c.g, c.starts, c.goals);
    p->set_immobile(0, true);
    Drive d = drive(*p, c.g, 200, 0, c.starts[0], [] { return false; });
    EXPECT_EQ(d.error, "");
    p->set_immobile(0, false);
    bool moved = false;
    drive(*p, c.g, 200, -1, -1, [&] { return moved = moved || p->current()[0] != c.starts[0]; });
    EXPECT_TRUE(moved);  // once mobile it heads for its goal
  }
}

TEST(Immobile, PibtNeverPushesOrPullsAnImmobileAgent)
{
  // Random crowded instances on a 5x4 grid: in every generated successor the immobile
  // agents stay and the step is valid (no vertex or swap conflict).
  Graph g = test::grid({".....", ".....", ".....", "....."});
  DistTable dist(g);
  Rng rng(7);
  int generated = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 4 + static_cast<int>(rng.next() % 12);
    std::vector<Vertex> cells(g.size());
    for (int v = 0; v < g.size(); ++v) cells[v] = v;
    rng.shuffle(cells.data(), g.size());
    Config from(cells.begin(), cells.begin() + n);
    rng.shuffle(cells.data(), g.size());
    Config goals(cells.begin(), cells.begin() + n);
    std::vector<uint8_t> immobile(n, 0);
    for (int i = 0; i < n; ++i) immobile[i] = rng.next() % 3 == 0;
    dist.set_goals(goals);
    for (bool swap : {false, true}) {
      Pibt pibt(g, dist, swap);
      pibt.set_goals(goals);
      pibt.set_immobile(immobile);
      std::vector<float> prio(n);
      std::vector<int32_t> order(n);
      init_priorities(from.data(), n, dist, prio.data());
      initial_order(prio.data(), n, order.data());
      Config to(n);
      if (!pibt.generate(from.data(), order.data(), nullptr, to.data(), rng)) continue;
      ++generated;
      EXPECT_EQ(Validator::check_transition(g, from, to), "") << "trial " << trial;
      for (int i = 0; i < n; ++i) {
        if (immobile[i]) {
          EXPECT_EQ(to[i], from[i]) << "trial " << trial << " agent " << i;
        }
      }
    }
  }
  EXPECT_GT(generated, 500);
}

TEST(Immobile, ARelaxedGoalThatCannotBeReachedIsNoFailure)
{
  // X (agent 0) stuck in a one-lane corridor; A and B behind it must swap in a two-cell
  // dead end: impossible. The search runs dry, the planner waits and claims no failure.
  // Once X is free, the 2x3 block beyond it lets A and B swap.
  Graph g = test::grid({".....", "@@..."});
  Config starts = test::at(g, {{2, 0}, {0, 0}, {1, 0}});
  Config goals = test::at(g, {{4, 1}, {1, 0}, {0, 0}});
  RtLacam rt(g, starts, goals);
  rt.set_immobile(0, true);
  Status s = Status::Searching;
  for (int k = 0; k < 100; ++k) s = rt.search(Budget::expansion_count(100));
  EXPECT_EQ(s, Status::Searching);
  EXPECT_FALSE(rt.exhausted());
  EXPECT_EQ(rt.next(), starts);
  EXPECT_LT(rt.explored(), 10u);  // bounded by what is reachable around the obstacle
  // Free again: X leaves, A and B swap, all finish.
  rt.set_immobile(0, false);
  Drive d = drive(rt, g, 200, -1, -1, [&] { return rt.at_goal(); });
  EXPECT_EQ(d.error, "");
  EXPECT_TRUE(rt.at_goal());
}

TEST(Immobile, RelaxedGoalTestSkipsAgentsCutOffOrOnTheObstacle)
{
  Graph g = test::grid({"....."});
  // X at 2; A at 0 -> 4 (cut off), B at 4 -> 3 (reachable), C at 3 -> 2 (X's cell).
  Config cur = test::at(g, {{2, 0}, {0, 0}, {4, 0}, {3, 0}});
  Config goals = test::at(g, {{0, 0}, {4, 0}, {3, 0}, {2, 0}});
  GoalTest t = relaxed_goal_test(g, cur, goals, {1, 0, 0, 0});
  ASSERT_TRUE(t);
  Config c = test::at(g, {{2, 0}, {1, 0}, {3, 0}, {4, 0}});
  EXPECT_TRUE(t(c.data()));   // only B must be on its goal
  Config d = test::at(g, {{2, 0}, {1, 0}, {4, 0}, {3, 0}});
  EXPECT_FALSE(t(d.data()));
  EXPECT_FALSE(relaxed_goal_test(g, cur, goals, {0, 0, 0, 0}));  // none immobile: default test
}

TEST(Immobile, AnImmobileAgentOnItsGoalIsNotMovedByRefinement)
{
  // X sits on its goal in the corridor's top lane, the others' shortest routes run through
  // it: LaCAM* refinement (LNS would replan X to step aside) must leave it in place.
  Corridor c;
  c.goals[0] = c.starts[0];
  // The same with iterative refinement instead of LNS (its SIPP would move X too).
  for (uint64_t seed = 0; seed < 10; ++seed) {
    LacamOptions o;
    o.seed = seed % 5;
    o.refine = true;
    o.iter_refine = seed >= 5;
    RtLacam rt(c.g, c.starts, c.goals, o);
    rt.set_immobile(0, true);
    for (int k = 0; k < 50; ++k) rt.search(Budget::expansion_count(200));  // refine a lot first
    Drive d = drive(rt, c.g, 300, 0, c.starts[0], [&] { return rt.at_goal(); });
    EXPECT_EQ(d.error, "") << "seed " << seed;
    EXPECT_TRUE(rt.at_goal()) << "seed " << seed;  // X is on its goal: the real goal test passes
  }
}

TEST(Immobile, DetourTableGoesAroundBlockedVertices)
{
  Graph g = test::grid({".....", "....."});
  DetourTable dt(g);
  EXPECT_FALSE(dt.active());
  dt.set_blocked({g.at(2, 0)});
  EXPECT_TRUE(dt.active());
  EXPECT_EQ(dt.get(g.at(4, 0), g.at(0, 0)), 6);  // down, along the bottom lane, up
  EXPECT_EQ(dt.get(g.at(4, 0), g.at(2, 0)), DistTable::kInf);  // the blocked vertex
  dt.set_blocked({g.at(2, 0), g.at(2, 1)});        // the corridor is cut
  EXPECT_EQ(dt.get(g.at(4, 0), g.at(0, 0)), DistTable::kInf);
  EXPECT_EQ(dt.get(g.at(4, 0), g.at(3, 1)), 2);
  dt.set_blocked({});
  EXPECT_FALSE(dt.active());
}

namespace {

// Distances to `goal` without the blocked vertices: one Bellman-Ford over the in-arcs (a
// move onto w costs g.move_cost(w): 1 without move costs).
std::vector<int32_t> bfs_around(const Graph& g, Vertex goal, const std::vector<Vertex>& blocked)
{
  std::vector<int32_t> d(g.size(), DistTable::kInf);
  auto is_blocked = [&](Vertex u) { return std::find(blocked.begin(), blocked.end(), u) != blocked.end(); };
  if (is_blocked(goal)) return d;
  d[goal] = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (Vertex w = 0; w < g.size(); ++w)
      if (d[w] < DistTable::kInf)
        for (Vertex u : g.in_neighbors(w))
          if (!is_blocked(u) && d[w] + g.move_cost(w) < d[u]) d[u] = d[w] + g.move_cost(w), changed = true;
  }
  return d;
}

void expect_detours_exact(bool costs);

}  // namespace

// The shadow search (immobile.hpp) against a BFS per goal on random grids with walls, one-way
// arcs included: never above the true detour distance, never below the plain one, and exact
// once the plain BFS has found every blocked vertex -- and it searches far fewer vertices.
TEST(Immobile, DetourTableMatchesABfsAroundTheBlockedVertices) { expect_detours_exact(false); }

// The same with move costs 1..4 (a slow lane's cells, graph.hpp): the shadow and its repair
// step by the cost of the vertex moved onto.
TEST(Immobile, DetourTableMatchesADijkstraAroundTheBlockedVerticesWithMoveCosts) { expect_detours_exact(true); }

namespace {
void expect_detours_exact(bool costs)
{
  std::mt19937 rng(costs ? 11 : 7);
  for (int trial = 0; trial < 60; ++trial) {
    const int w = 4 + static_cast<int>(rng() % 9), h = 3 + static_cast<int>(rng() % 7);
    std::vector<bool> free(w * h);
    for (size_t k = 0; k < free.size(); ++k) free[k] = rng() % 5 != 0;
    Graph grid = Graph::from_grid(w, h, free);
    if (grid.size() < 6) continue;
    Graph g = grid;
    if (trial % 3 == 2) {  // some arcs one-way (kept strongly connected enough by the reverse of the rest)
      std::vector<std::pair<Vertex, Vertex>> arcs;
      for (Vertex u = 0; u < grid.size(); ++u)
        for (Vertex v : grid.neighbors(u))
          if (u < v) {
            arcs.push_back({u, v});
            if (rng() % 4) arcs.push_back({v, u});
          }
      g = Graph::from_arcs(grid.size(), arcs);
    }
    if (costs) {
      std::vector<uint8_t> c(g.size());
      for (uint8_t& k : c) k = static_cast<uint8_t>(1 + rng() % 4);
      g.set_move_costs(c);
    }
    std::vector<Vertex> blocked;
    for (int k = 1 + static_cast<int>(rng() % 4); k > 0; --k) blocked.push_back(static_cast<Vertex>(rng() % g.size()));
    for (int q = 0; q < 3; ++q) {
      const Vertex goal = static_cast<Vertex>(rng() % g.size());
      const std::vector<int32_t> exact = bfs_around(g, goal, blocked);
      DistTable plain(g);
      DetourTable dt(g, &plain);
      dt.set_blocked(blocked);
      std::vector<Vertex> order(g.size());
      for (Vertex v = 0; v < g.size(); ++v) order[v] = v;
      std::shuffle(order.begin(), order.end(), rng);
      for (Vertex v : order) {
        const int32_t d = dt.get(goal, v);
        EXPECT_LE(d, exact[v]) << "trial " << trial << " v " << v;
        if (exact[v] < DistTable::kInf) {
          EXPECT_GE(d, plain.from_goal(goal, v)) << "trial " << trial << " v " << v;
        }
      }
      for (Vertex v : order) ASSERT_EQ(dt.get(goal, v), exact[v]) << "trial " << trial << " goal " << goal << " v " << v;
    }
  }
}
}  // namespace

// The cost that made a stuck replan blow the step budget at 1000 AGVs: with one stuck AGV,
// the detours of 300 agents' goals on a warehouse-like grid (shelf rows, aisles) search a
// fraction of the 300 BFS over the whole grid (one per goal) that they used to be: 12 %
// here, with the AGV stuck in the main cross aisle that funnels many goals' paths.
TEST(Immobile, DetoursSearchOnlyTheShadowOfTheBlockedVertex)
{
  std::vector<std::string> rows;
  for (int y = 0; y < 31; ++y) {
    std::string r(61, '.');
    if (y % 3 != 0)
      for (int x = 2; x < 59; ++x)
        if (x % 10 != 0) r[x] = '@';  // shelves, cut by a cross aisle every 10 columns
    rows.push_back(r);
  }
  Graph g = test::grid(rows);
  std::mt19937 rng(3);
  DistTable plain(g);
  DetourTable dt(g, &plain);
  dt.set_blocked({g.at(30, 15)});  // a stuck AGV in the middle of the main cross aisle
  const int agents = 300;
  for (int a = 0; a < agents; ++a) {
    const Vertex goal = static_cast<Vertex>(rng() % g.size()), at = static_cast<Vertex>(rng() % g.size());
    dt.get(goal, at);
    for (Vertex u : g.neighbors(at)) dt.get(goal, u);
  }
  EXPECT_LT(dt.searched(), static_cast<uint64_t>(agents) * g.size() / 5) << dt.searched() << " of " << agents * g.size();
  EXPECT_GT(dt.searched(), 0u);  // some agents' paths do run through it
}

// Past the deadline of the plain tables' cache no shadow is searched: the plain distance
// (a lower bound) until a query before a deadline searches it.
TEST(Immobile, NoShadowSearchPastTheCachesDeadline)
{
  Graph g = test::grid({".....", "....."});
  DistTable plain(g);
  DetourTable dt(g, &plain);
  dt.set_blocked({g.at(2, 0)});
  plain.cache()->set_deadline(DistCache::Deadline::clock::now() - std::chrono::seconds(1));
  EXPECT_EQ(dt.get(g.at(4, 0), g.at(0, 0)), 4);  // plain: straight through the blocked cell
  EXPECT_EQ(dt.searched(), 0u);
  plain.cache()->set_deadline(DistCache::Deadline::max());
  EXPECT_EQ(dt.get(g.at(4, 0), g.at(0, 0)), 6);  // around it
  EXPECT_GT(dt.searched(), 0u);
}

TEST(Immobile, AnAgentOutOfRangeIsAClearError)
{
  Corridor c;
  for (Solver s : {Solver::RtLacam, Solver::Naive, Solver::Pibt}) {
    auto p = make_planner(s, c.g, c.starts, c.goals);
    try {
      p->set_immobile(5, true);
      ADD_FAILURE() << to_string(s) << ": no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "set_immobile: agent 5 out of range (0..4)");
    }
    EXPECT_THROW(p->set_immobile(-1, true), std::invalid_argument);
  }
}

// A corridor with three stuck agents (0, 1, 2 in the top lane's middle), the others passing.
struct ThreeStuck {
  Graph g = test::grid({"..........", ".........."});
  Config starts = test::at(g, {{3, 0}, {4, 0}, {6, 0}, {0, 0}, {9, 0}, {0, 1}, {9, 1}});
  Config goals = test::at(g, {{3, 1}, {4, 1}, {6, 1}, {9, 0}, {0, 0}, {9, 1}, {0, 1}});
  std::vector<uint8_t> marks{1, 1, 1, 0, 0, 0, 0};
};

TEST(Immobile, BatchMarksRestartTheSearchOnceForAllAgents)
{
  // The stuck-AGV replan marks all its stuck AGVs in one SUMO step: one restart (a tree
  // reset and a relaxed goal test each, ~0.3 ms at 1000 agents), not one per agent.
  ThreeStuck c;
  RtLacam batch(c.g, c.starts, c.goals), single(c.g, c.starts, c.goals);
  const uint64_t r0 = batch.restarts();
  batch.set_immobile(c.marks);
  EXPECT_EQ(batch.restarts(), r0 + 1);
  batch.set_immobile(c.marks);  // unchanged: no restart
  EXPECT_EQ(batch.restarts(), r0 + 1);
  for (int i = 0; i < 3; ++i) single.set_immobile(i, true);
  EXPECT_EQ(single.restarts(), r0 + 3);
  // The same planner state either way: the same plan, every step valid, the stuck ones
  // fixed, and the others through.
  for (int s = 0; s < 60 && !(batch.at_goal() && single.at_goal()); ++s) {
    batch.search(Budget::expansion_count(20));
    single.search(Budget::expansion_count(20));
    const Config from = batch.current(), next = batch.next();
    ASSERT_EQ(next, single.next()) << "step " << s;
    EXPECT_EQ(Validator::check_transition(c.g, from, next), "") << "step " << s;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(next[i], c.starts[i]) << "step " << s;
    batch.commit();
    single.commit();
  }
  for (int i = 3; i < 7; ++i) EXPECT_EQ(batch.current()[i], c.goals[i]) << "agent " << i;
  // Clearing all marks at once: one restart, and everyone finishes (completeness back).
  const uint64_t r1 = batch.restarts();
  batch.set_immobile(std::vector<uint8_t>(7, 0));
  EXPECT_EQ(batch.restarts(), r1 + 1);
  Drive d = drive(batch, c.g, 300, -1, -1, [&] { return batch.at_goal(); });
  EXPECT_EQ(d.error, "");
  EXPECT_TRUE(batch.at_goal());
}

TEST(Immobile, BatchMarksEqualMarksOneByOneInEveryCellSolver)
{
  ThreeStuck c;
  for (Solver s : {Solver::RtLacam, Solver::Naive, Solver::Pibt}) {
    auto batch = make_planner(s, c.g, c.starts, c.goals);
    auto single = make_planner(s, c.g, c.starts, c.goals);
    batch->set_immobile(c.marks);
    for (int i = 0; i < 3; ++i) single->set_immobile(i, true);
    for (int k = 0; k < 40; ++k) {
      batch->search(Budget::expansion_count(20));
      single->search(Budget::expansion_count(20));
      const Config next = batch->next();
      ASSERT_EQ(next, single->next()) << batch->name() << " step " << k;
      EXPECT_EQ(Validator::check_transition(c.g, batch->current(), next), "") << batch->name();
      for (int i = 0; i < 3; ++i) EXPECT_EQ(next[i], c.starts[i]) << batch->name() << " step " << k;
      batch->commit();
      single->commit();
    }
    EXPECT_THROW(batch->set_immobile(std::vector<uint8_t>(3, 1)), std::invalid_argument) << batch->name();
  }
}

TEST(Immobile, RestartAtAMovedConfigurationIsOneRestartAndPlansOnFromThere)
{
  // The stuck-AGV replan restarts the planner where the cut plan leaves the agents (moves
  // it did not plan) with the stuck ones immobile: one restart, where a fresh planner costs
  // its construction plus a restart per mark. The plan from there is valid, keeps the
  // stuck ones in place, and once they are free everybody finishes.
  ThreeStuck c;
  Config at = c.starts;
  at[3] = test::at(c.g, {{1, 0}})[0];  // agent 3 moved on behind the planner's back
  at[5] = test::at(c.g, {{1, 1}})[0];
  for (Solver s : {Solver::RtLacam, Solver::Naive, Solver::Pibt}) {
    auto p = make_planner(s, c.g, c.starts, c.goals);
    for (int k = 0; k < 5; ++k) p->search(Budget::expansion_count(20)), p->commit();  // some plan of its own first
    const auto* rt = dynamic_cast<const RtLacam*>(p.get());
    const uint64_t r0 = rt ? rt->restarts() : 0;
    ASSERT_TRUE(p->restart_at(at, c.goals, {}, c.marks)) << p->name();
    if (rt) {
      EXPECT_EQ(rt->restarts(), r0 + 1);
    }
    EXPECT_EQ(p->current(), at) << p->name();
    Config prev = at;
    for (int k = 0; k < 60; ++k) {
      p->search(Budget::expansion_count(20));
      const Config next = p->next();
      EXPECT_EQ(Validator::check_transition(c.g, prev, next), "") << p->name() << " step " << k;
      for (int i = 0; i < 3; ++i) EXPECT_EQ(next[i], c.starts[i]) << p->name() << " step " << k;
      p->commit();
      prev = next;
    }
    ASSERT_TRUE(p->restart_at(p->current(), c.goals, {}, std::vector<uint8_t>(7, 0)));
    Drive d = drive(*p, c.g, 400, -1, -1, [&] { return p->at_goal(); });
    EXPECT_EQ(d.error, "") << p->name();
    EXPECT_TRUE(p->at_goal()) << p->name();
    EXPECT_THROW(p->restart_at(Config(3, 0), c.goals, {}, c.marks), std::invalid_argument) << p->name();
  }
}
