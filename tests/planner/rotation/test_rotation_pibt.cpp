// The rotation-native planner (pibt-rot): exact (cell, heading) distances against a brute
// force search, a lone robot's shortest rotation path, and LoRR-valid joint actions over
// lifelong runs with several seeds.
#include <gtest/gtest.h>

#include <chrono>
#include <deque>
#include <string>
#include <vector>

#include "planner/rng.hpp"
#include "planner/rotation/epibt.hpp"
#include "planner/rotation/rotation_dist.hpp"
#include "planner/rotation/rotation_pibt.hpp"
#include "planner/validator.hpp"
#include "grid.hpp"

using planner::Config;
using planner::Graph;
using planner::RotationDist;
using planner::RotationPibt;
using planner::Vertex;

namespace {

using test::random_grid;

// Brute force: forward BFS over (cell, heading) from (v, o) with the MAPF_T moves, until a
// state on `goal`; 0xFFFF when none is reachable.
uint16_t brute(const Graph& g, Vertex v, int o, Vertex goal)
{
  static const int dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
  std::vector<int> d(static_cast<size_t>(g.size()) * 4, -1);
  std::deque<int> q{v * 4 + o};
  d[static_cast<size_t>(v * 4 + o)] = 0;
  while (!q.empty()) {
    const int s = q.front();
    q.pop_front();
    const Vertex u = s / 4;
    const int h = s % 4;
    if (u == goal) return static_cast<uint16_t>(d[static_cast<size_t>(s)]);
    const Vertex f = g.at(g.cell_x(u) + dx[h], g.cell_y(u) + dy[h]);
    for (int n : {f >= 0 && g.adjacent(u, f) ? f * 4 + h : -1, u * 4 + (h + 1) % 4, u * 4 + (h + 3) % 4})
      if (n >= 0 && d[static_cast<size_t>(n)] < 0) {
        d[static_cast<size_t>(n)] = d[static_cast<size_t>(s)] + 1;
        q.push_back(n);
      }
  }
  return RotationDist::kInf;
}

// One MAPF_T step as LoRR applies it; "" when `next` and `heads` are its result.
std::string check_actions(const RotationPibt& p, const Config& cur, const std::vector<int>& heads, const Config& next,
                          const std::vector<int>& next_heads)
{
  const std::string& a = p.actions();
  for (size_t i = 0; i < cur.size(); ++i) {
    const int o = heads[i];
    Vertex v = cur[i];
    int h = o;
    if (a[i] == 'F') v = p.dist().ahead(cur[i], o);
    else if (a[i] == 'R') h = (o + 1) % 4;
    else if (a[i] == 'C') h = (o + 3) % 4;
    else if (a[i] != 'W') return "unknown action";
    if (v < 0) return "agent " + std::to_string(i) + " forward into a wall";
    if (v != next[i] || h != next_heads[i]) return "agent " + std::to_string(i) + " action " + a[i] + " mismatch";
  }
  return "";
}

}  // namespace

TEST(RotationDist, EqualsBruteForceOverCellHeadingStates)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = random_grid(7, 6, 25, seed);
    RotationDist dist(g);
    for (Vertex goal = 0; goal < g.size(); goal += 3) {
      RotationDist::Table* t = dist.table(goal);
      // Query in a scattered order: the lazy BFS must be exact whatever it was grown for.
      for (Vertex v = g.size() - 1; v >= 0; --v)
        for (int o = 0; o < 4; ++o) ASSERT_EQ(dist.get(t, v, o), brute(g, v, o, goal)) << "seed " << seed << " goal " << goal << " v " << v << " o " << o;
    }
  }
}

TEST(RotationDist, TurnsCostStepsAnyHeadingOnTheGoalAndWallsAreUnreachable)
{
  // From (0,1) facing east to (2,0): east then north costs F F C F = 4 steps; north then
  // east costs C F R F F = 5.
  const Graph g = test::grid({"...", "..."});
  RotationDist dist(g);
  RotationDist::Table* t = dist.table(g.at(2, 0));
  EXPECT_EQ(dist.get(t, g.at(0, 1), 0), 4);
  EXPECT_EQ(dist.get(t, g.at(0, 1), 2), 5);  // facing west: R F R F F (a half turn first costs 6)
  EXPECT_EQ(dist.get(t, g.at(2, 0), 1), 0);  // on the goal in any heading
  EXPECT_EQ(dist.get(t, g.at(1, 0), 2), 3);  // half turn, then forward
  // Unreachable: a walled-off cell.
  const Graph h = test::grid({".@."});
  RotationDist d2(h);
  EXPECT_EQ(d2.get(d2.table(h.at(2, 0)), h.at(0, 0), 0), RotationDist::kInf);
}

TEST(RotationDist, UnpinnedTablesAreDroppedBeyondTheCap)
{
  const Graph g = random_grid(6, 6, 0, 1);
  RotationDist dist(g, 2);
  RotationDist::Table* keep = dist.table(0);
  dist.pin(keep);
  for (Vertex goal = 1; goal < 6; ++goal) dist.table(goal);
  dist.trim();
  EXPECT_EQ(dist.num_tables(), 2u);
  EXPECT_EQ(dist.get(dist.table(0), 0, 0), 0);  // the pinned one survived
  EXPECT_EQ(keep, dist.table(0));
}

TEST(RotationDist, PrefetchGrowsQueuedTablesToCompletionAndPinsThem)
{
  const Graph g = random_grid(8, 8, 20, 3);
  RotationDist dist(g, 1);
  dist.prefetch({0, g.size() - 1});
  EXPECT_EQ(dist.pending(), 2u);
  EXPECT_TRUE(dist.precompute(std::chrono::steady_clock::now()));  // deadline passed: work remains
  EXPECT_FALSE(dist.precompute(std::chrono::steady_clock::time_point::max()));
  EXPECT_EQ(dist.pending(), 0u);
  dist.trim();
  EXPECT_EQ(dist.num_tables(), 2u);  // over the cap of 1, but pinned by the queue
  RotationDist::Table* t = dist.table(g.size() - 1);
  EXPECT_TRUE(t->done());
  for (Vertex v = 0; v < g.size(); ++v)
    for (int o = 0; o < 4; ++o) ASSERT_EQ(t->dist[static_cast<size_t>(v) * 4 + o], brute(g, v, o, g.size() - 1));
  dist.prefetch({});  // unpinned: the cap applies again
  dist.trim();
  EXPECT_EQ(dist.num_tables(), 1u);
}

TEST(RotationPibt, LoneRobotReachesItsGoalInTheRotationShortestNumberOfSteps)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = random_grid(9, 7, 20, seed + 10);
    planner::Rng rng(seed);
    for (int trial = 0; trial < 5; ++trial) {
      const Vertex s = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      const Vertex goal = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      const uint16_t want = brute(g, s, 0, goal);  // robots start facing east
      if (want == RotationDist::kInf) continue;
      RotationPibt p(g, {s}, {goal}, seed);
      int steps = 0;
      while (!p.at_goal() && steps < 200) {
        p.search(planner::Budget{});
        p.commit();
        ++steps;
      }
      EXPECT_EQ(steps, want) << "seed " << seed << " from " << s << " to " << goal;
    }
  }
}

TEST(RotationPibt, EveryLifelongStepIsAValidLorrJointActionAndRobotsArrive)
{
  // 25 robots on a 12 x 10 grid with 15 % obstacles (dense: a quarter of the free cells),
  // new random goals on arrival, 300 steps, several seeds.
  for (uint64_t seed = 0; seed < 6; ++seed) {
    const Graph g = random_grid(12, 10, 15, seed + 100);
    std::vector<int> comp_id = g.components();
    planner::Rng rng(seed);
    std::vector<Vertex> free_cells;
    for (Vertex v = 0; v < g.size(); ++v) free_cells.push_back(v);
    rng.shuffle(free_cells.data(), static_cast<int>(free_cells.size()));
    const int n = 25;
    Config starts(free_cells.begin(), free_cells.begin() + n), goals(static_cast<size_t>(n));
    auto new_goal = [&](int i, Vertex from) {  // a reachable cell other than `from`
      for (;;) {
        const Vertex v = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
        if (v != from && comp_id[v] == comp_id[from]) return goals[i] = v;
      }
    };
    for (int i = 0; i < n; ++i) new_goal(i, starts[i]);
    RotationPibt p(g, starts, goals, seed);
    p.set_back_last(seed % 2 == 1);  // both rankings of a robot asked to vacate its cell
    long arrivals = 0, forwards = 0, turns = 0;
    for (int t = 1; t <= 300; ++t) {
      const Config cur = p.current();
      const std::vector<int> heads = p.headings();
      p.search(planner::Budget{});
      const Config next = p.next();
      ASSERT_EQ(planner::Validator::check_transition(g, cur, next), "") << "seed " << seed << " step " << t;
      const std::string acts = p.actions();
      p.commit();
      ASSERT_EQ(check_actions(p, cur, heads, p.current(), p.headings()), "") << "seed " << seed << " step " << t;
      ASSERT_EQ(p.current(), next);
      for (char a : acts) forwards += a == 'F', turns += a == 'R' || a == 'C';
      bool changed = false;
      for (int i = 0; i < n; ++i)
        if (p.current()[i] == goals[i]) ++arrivals, new_goal(i, goals[i]), changed = true;
      if (changed) p.set_goals(goals);
    }
    EXPECT_GT(arrivals, 50) << "seed " << seed;  // measured 100-200
    EXPECT_GT(forwards, 0);
    EXPECT_GT(turns, 0);
  }
}

// Foreign pockets (RotationPibt::set_pockets, tasks.urgency.pocket_cost; the cell PIBT's
// rule): robot 1 stands on its goal in a corridor above a one-cell dead end, facing south
// into it; robot 0 (west-bound, first) asks it to vacate. Going into the stub costs it the
// fewest steps (no turn), so without pockets it drives in (how idle AGVs ended up blocking
// station stubs at 1000 AGVs); with the stub labelled a pocket that is not its goal's it
// turns west instead. A robot whose goal is in the pocket still enters it.
TEST(RotationPibt, AForeignPocketIsTheLastResortOfAPushedRobot)
{
  const Graph g = test::grid({".....", "@@.@@"});
  const Vertex stub = g.at(2, 1), mouth = g.at(2, 0);
  auto step = [&](bool pockets, Vertex goal1) {
    RotationPibt p(g, {g.at(3, 0), mouth}, {g.at(0, 0), goal1}, 0);
    p.set_headings({2, 1});  // robot 0 west, robot 1 south (facing the stub)
    if (pockets) p.set_pockets(test::pocket_labels(g, {stub}, stub), 100.0f);
    p.search(planner::Budget{});
    return std::make_pair(p.actions(), p.next());
  };
  const auto [a_off, n_off] = step(false, mouth);
  EXPECT_EQ(a_off, "FF");  // both move: robot 1 into the stub
  EXPECT_EQ(n_off[1], stub);
  const auto [a_on, n_on] = step(true, mouth);
  EXPECT_EQ(a_on, "WR");   // robot 1 turns toward the corridor's west cell, robot 0 waits for it
  EXPECT_EQ(n_on[1], mouth);
  // Robot 1 bound for the stub: its own pocket costs nothing.
  const auto [a_own, n_own] = step(true, stub);
  EXPECT_EQ(n_own[1], stub);
}

// The pocket exit rule with leavers first (planner/rotation/pocket_exit.hpp), as on
// large_warehouse_lifelong: robot 0 stands on a station at the end of a three-cell stub,
// facing the wall, its next goal outside; four older robots (hint 5), all bound for the
// station, crowd the stub's mouth: on it facing in, below it, and on the cross aisle at both
// sides. Without the rule they follow each other in and face the station: robot 0 needs a
// half turn and the line to back out, which it never does (its way to the station is
// ahead), so robot 0 is still walled in after 40 steps. With it nobody goes deeper while
// robot 0 must leave, robot 0 plans first and pushes the mouth's robot aside, gets out,
// and then a robot of the crowd reaches the station.
TEST(RotationPibt, ALeaverGetsOutOfAStubBeforeAnyoneGoesDeeper)
{
  const Graph g = test::grid({"@@.@@", "@@.@@", "@@.@@", ".....", "@@.@@", "@@.@@"});
  const Vertex station = g.at(2, 0), mouth = g.at(2, 3);
  const std::vector<Vertex> pocket = test::pocket_labels(g, {station, g.at(2, 1), g.at(2, 2)}, station);
  for (bool rule : {false, true}) {
    const Config starts{station, mouth, g.at(2, 4), g.at(1, 3), g.at(3, 3)};
    RotationPibt p(g, starts, Config(5, station), 0);
    p.set_headings({3, 3, 3, 0, 2});  // robot 0 faces the wall; the crowd faces the mouth
    p.set_back_last(true);
    p.set_pocket_exit(rule);
    p.set_pockets(pocket, 0.0f);  // labels only: no foreign-pocket cost
    p.set_priority_hint({0.0f, 5.0f, 5.0f, 5.0f, 5.0f});
    p.set_goals({g.at(0, 3), station, station, station, station});  // robot 0's next errand is outside
    int out = -1, in = -1;  // steps until robot 0 is out of the stub, another robot on the station
    bool deeper = false;    // a robot of the crowd went into the stub while robot 0 was in it
    for (int t = 1; t <= 40; ++t) {
      p.search(planner::Budget{});
      p.commit();
      for (int i = 1; i < 5; ++i)
        deeper = deeper || (out < 0 && pocket[static_cast<size_t>(p.current()[static_cast<size_t>(i)])] >= 0);
      if (out < 0 && pocket[static_cast<size_t>(p.current()[0])] < 0) out = t;
      for (int i = 1; i < 5; ++i)
        if (in < 0 && p.current()[static_cast<size_t>(i)] == station) in = t;
    }
    EXPECT_EQ(deeper, !rule);
    if (rule) {
      EXPECT_GT(out, 0);
      EXPECT_GT(in, out);
    }
  }
}

TEST(RotationPibt, NeedsAGridAndDistinctStarts)
{
  const Graph line = Graph::from_edges(2, {{0, 1}});
  EXPECT_THROW(RotationPibt(line, {0}, {1}), std::invalid_argument);
  const Graph g = test::grid({"..."});
  EXPECT_THROW(RotationPibt(g, {0, 0}, {1, 2}), std::invalid_argument);
}

// The grid graph g with its 4-neighbour pairs made one-way where `dir` says so: dir(v, u) for
// a pair (v, u) with u right of or below v returns 0 (both ways), 1 (v -> u only) or 2
// (u -> v only).
template <class Dir>
Graph with_directions(const Graph& g, Dir dir)
{
  std::vector<std::pair<Vertex, Vertex>> arcs;
  std::vector<int32_t> cells;
  for (Vertex v = 0; v < g.size(); ++v) {
    cells.push_back(g.cell_y(v) * g.width() + g.cell_x(v));
    for (Vertex u : {g.at(g.cell_x(v) + 1, g.cell_y(v)), g.at(g.cell_x(v), g.cell_y(v) + 1)}) {
      if (u < 0) continue;
      const int d = dir(v, u);
      if (d != 2) arcs.push_back({v, u});
      if (d != 1) arcs.push_back({u, v});
    }
  }
  Graph out = Graph::from_arcs(g.size(), arcs);
  out.attach_grid(g.width(), g.height(), cells);
  return out;
}

// Directed graphs (one-way aisles): the rotation distances follow the arcs (a forward move
// only along one, the backward search over the arcs into a cell), kInf where the goal
// cannot be reached along them. Fails if the tables ignore directions (or refuse them).
TEST(DirectedGraph, RotationDistFollowsOneWayArcs)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    planner::Rng rng(seed + 7);
    const Graph g = with_directions(random_grid(7, 6, 15, seed + 30), [&](Vertex, Vertex) { return static_cast<int>(rng.below(4)) % 3; });
    ASSERT_TRUE(g.directed());
    RotationDist dist(g);
    long unreachable = 0;
    for (Vertex goal = 0; goal < g.size(); goal += 2) {
      RotationDist::Table* t = dist.table(goal);
      for (Vertex v = g.size() - 1; v >= 0; --v)
        for (int o = 0; o < 4; ++o) {
          const uint16_t want = brute(g, v, o, goal);
          unreachable += want == RotationDist::kInf;
          ASSERT_EQ(dist.get(t, v, o), want) << "seed " << seed << " goal " << goal << " v " << v << " o " << o;
        }
    }
    EXPECT_GT(unreachable, 0) << "seed " << seed << ": the sample should hold states cut off by one-way arcs";
  }
}

// pibt-rot and epibt on a one-way loop (clockwise: east along the top, south on the right,
// west along the bottom, north on the left): every step moves along arcs only (the
// validator checks adjacency on the directed graph) and every robot reaches its goal.
TEST(DirectedGraph, RotationPlannersMoveAlongOneWayArcsOnly)
{
  const Graph ring = test::grid({".....", ".@@@.", "....."});
  const Graph g = with_directions(ring, [&](Vertex v, Vertex u) {
    const int y = ring.cell_y(v), x = ring.cell_x(v);
    if (ring.cell_y(u) == y) return y == 0 ? 1 : 2;  // top row east, bottom row west
    return x == ring.width() - 1 ? 1 : 2;             // right column south, left column north
  });
  const Config starts = {g.at(0, 0), g.at(4, 1), g.at(2, 2)}, goals = {g.at(3, 2), g.at(1, 0), g.at(0, 1)};
  for (int kind = 0; kind < 2; ++kind) {
    std::unique_ptr<planner::RotationPlanner> p;
    if (kind == 0) p = std::make_unique<RotationPibt>(g, starts, goals, 1);
    else {
      // Age priority (the controller's default): with the paper's distance priority a robot
      // resting on its goal outranks one that must pass it and never yields (not complete).
      planner::EpibtOptions o;
      o.priority = planner::EpibtOptions::Priority::Age;
      p = std::make_unique<planner::Epibt>(g, starts, goals, o);
    }
    Config cur = starts;
    std::vector<bool> arrived(starts.size(), false);
    for (int t = 1; t <= 60; ++t) {
      p->search(planner::Budget{});
      const Config next = p->next();
      ASSERT_EQ(planner::Validator::check_transition(g, cur, next), "") << p->name() << " step " << t;
      p->commit();
      cur = p->current();
      for (size_t i = 0; i < cur.size(); ++i) arrived[i] = arrived[i] || cur[i] == goals[i];
    }
    for (size_t i = 0; i < arrived.size(); ++i) EXPECT_TRUE(arrived[i]) << p->name() << ": robot " << i << " never reached its goal";
  }
}
