// Windowed LNS for the rotation model (wppl): space-time A* over (cell, heading, t)
// against a lone robot's RotationDist and against brute force (every action sequence) with
// reservations; Wppl's steps are valid LoRR joint actions (Validator + MAPF_T replay) and
// its windows conflict-free over hundreds of lifelong steps at high density; LNS never
// makes the windowed objective worse; no LNS = pibt-rot's steps; deterministic.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "planner/rng.hpp"
#include "planner/rotation/rotation_dist.hpp"
#include "planner/rotation/rotation_pibt.hpp"
#include "planner/rotation/st_astar_rot.hpp"
#include "planner/validator.hpp"
#include "planner/rotation/wppl.hpp"
#include "grid.hpp"

using planner::Config;
using planner::Graph;
using planner::RotationDist;
using planner::RotPath;
using planner::RotReservations;
using planner::RotState;
using planner::StAstarRot;
using planner::Vertex;
using planner::Wppl;
using planner::WpplOptions;

namespace {

using test::random_grid;

// One MAPF_T action from s: F into the cell ahead (-1 if none), R, C, W.
RotState apply(const RotationDist& d, RotState s, char a)
{
  if (a == 'F') return {d.ahead(s.v, s.o), s.o};
  if (a == 'R') return {s.v, (s.o + 1) % 4};
  if (a == 'C') return {s.v, (s.o + 3) % 4};
  return s;
}

// "" when p is a sequence of MAPF_T moves from s free of conflicts with res.
std::string check_path(const RotationDist& d, const RotReservations& res, RotState s, const RotPath& p)
{
  if (static_cast<int>(p.size()) != res.window() + 1 || !(p[0] == s)) return "bad start or length";
  for (int t = 0; t < res.window(); ++t) {
    bool legal = false;
    for (char a : std::string("FRCW")) legal |= apply(d, p[t], a) == p[t + 1] && p[t + 1].v >= 0;
    if (!legal) return "illegal move at " + std::to_string(t);
    if (res.at(p[t + 1].v, t + 1) >= 0) return "vertex conflict at " + std::to_string(t + 1);
    const int b = res.at(p[t + 1].v, t);
    if (p[t + 1].v != p[t].v && b >= 0 && res.at(p[t].v, t + 1) == b) return "swap at " + std::to_string(t);
  }
  return "";
}

// Brute force: every action sequence of length W, the least windowed cost of a
// conflict-free one (-1: none).
int64_t brute(const RotationDist& d, RotationDist::Table* tab, Vertex goal, const RotReservations& res, RotState s)
{
  const int w = res.window();
  int64_t best = -1;
  RotPath p(static_cast<size_t>(w) + 1);
  p[0] = s;
  auto rec = [&](auto&& self, int t) -> void {
    if (t == w) {
      if (check_path(d, res, s, p).empty()) {
        const int64_t c = planner::windowed_cost(d, tab, goal, p);
        if (best < 0 || c < best) best = c;
      }
      return;
    }
    for (char a : std::string("FRCW")) {
      const RotState n = apply(d, p[t], a);
      if (n.v < 0) continue;
      p[t + 1] = n;
      self(self, t + 1);
    }
  };
  rec(rec, 0);
  return best;
}

// A random walk of MAPF_T moves (conflicts among walks do not matter here).
RotPath random_walk(const RotationDist& d, RotState s, int w, planner::Rng& rng)
{
  RotPath p{s};
  while (static_cast<int>(p.size()) <= w) {
    RotState n = apply(d, p.back(), "FFRCW"[rng.below(5)]);
    if (n.v < 0) n = p.back();
    p.push_back(n);
  }
  return p;
}

// One MAPF_T joint step as LoRR applies it: "" when (next, next_heads) is its result.
std::string check_actions(const RotationDist& d, const std::string& a, const Config& cur, const std::vector<int>& heads,
                          const Config& next, const std::vector<int>& next_heads)
{
  for (size_t i = 0; i < cur.size(); ++i) {
    if (std::string("FRCW").find(a[i]) == std::string::npos) return "unknown action";
    const RotState n = apply(d, {cur[i], heads[i]}, a[i]);
    if (n.v < 0) return "agent " + std::to_string(i) + " forward into a wall";
    if (n.v != next[i] || n.o != next_heads[i]) return "agent " + std::to_string(i) + " action " + a[i] + " mismatch";
  }
  return "";
}

// Every transition of a window: legal MAPF_T moves, no vertex or swap conflict on cells.
std::string check_window(const Graph& g, const RotationDist& d, const std::vector<RotPath>& plan)
{
  if (plan.empty()) return "";
  const int w = static_cast<int>(plan[0].size()) - 1;
  for (int t = 0; t < w; ++t) {
    Config a, b;
    for (size_t i = 0; i < plan.size(); ++i) {
      bool legal = false;
      for (char c : std::string("FRCW")) legal |= apply(d, plan[i][t], c) == plan[i][t + 1];
      if (!legal) return "agent " + std::to_string(i) + " illegal move at t " + std::to_string(t);
      a.push_back(plan[i][t].v), b.push_back(plan[i][t + 1].v);
    }
    const std::string e = planner::Validator::check_transition(g, a, b);
    if (!e.empty()) return "t " + std::to_string(t) + ": " + e;
  }
  return "";
}

}  // namespace

TEST(StAstarRot, LoneRobotCostEqualsRotationDistanceAndPathIsLegal)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = random_grid(9, 8, 20, seed + 7);
    RotationDist d(g);
    StAstarRot astar(d);
    RotReservations res;
    planner::Rng rng(seed);
    for (int w : {3, 8, 15}) {
      res.reset(g.size(), w);
      for (int trial = 0; trial < 20; ++trial) {
        const RotState s{static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size()))), static_cast<int>(rng.below(4))};
        const Vertex goal = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
        RotationDist::Table* t = d.table(goal);
        const uint16_t h = d.get(t, s.v, s.o);
        if (h == RotationDist::kInf) continue;
        RotPath p;
        // Alone, the windowed cost is the distance: the arrival time within the window,
        // else W + h(end) = h along a shortest path.
        ASSERT_EQ(astar.plan(s, goal, t, res, p), h) << "seed " << seed << " w " << w << " trial " << trial;
        ASSERT_EQ(check_path(d, res, s, p), "");
        ASSERT_EQ(planner::windowed_cost(d, t, goal, p), h);
      }
    }
  }
}

TEST(StAstarRot, EqualsBruteForceAgainstReservationsOnTinyMaps)
{
  int compared = 0, blocked = 0;
  for (uint64_t seed = 0; seed < 12; ++seed) {
    const Graph g = random_grid(4, 3, 15, seed + 40);
    RotationDist d(g);
    StAstarRot astar(d);
    planner::Rng rng(seed);
    const int w = 5;  // 4^5 action sequences per start
    RotReservations res;
    for (int trial = 0; trial < 6; ++trial) {
      res.reset(g.size(), w);
      const RotState s{static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size()))), static_cast<int>(rng.below(4))};
      // Up to 3 others walking about, none starting on s.
      for (int k = 0; k < 3; ++k) {
        const Vertex v = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
        if (v == s.v || res.at(v, 0) >= 0) continue;
        res.add(k, random_walk(d, {v, static_cast<int>(rng.below(4))}, w, rng));
      }
      const Vertex goal = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      RotationDist::Table* t = d.table(goal);
      if (d.get(t, s.v, s.o) == RotationDist::kInf) continue;
      RotPath p;
      const int64_t got = astar.plan(s, goal, t, res, p);
      const int64_t want = brute(d, t, goal, res, s);
      ASSERT_EQ(got, want) << "seed " << seed << " trial " << trial;
      if (got >= 0) {
        ASSERT_EQ(check_path(d, res, s, p), "");
        ASSERT_EQ(planner::windowed_cost(d, t, goal, p), got);
      }
      ++compared, blocked += got < 0 || got > d.get(t, s.v, s.o);
    }
  }
  EXPECT_GT(compared, 40);
  EXPECT_GT(blocked, 3);  // the reservations did get in the way in some trials
}

namespace {

// A dense lifelong run: n robots on a w x h grid, new random goals on arrival.
struct DenseRun {
  Graph g;
  std::vector<int> comp;
  planner::Rng rng;
  Config starts, goals;
  DenseRun(int w, int h, int pct, int n, uint64_t seed) : g(random_grid(w, h, pct, seed + 100)), comp(g.components()), rng(seed)
  {
    const std::vector<Vertex> cells = test::shuffled_cells(g, rng);
    starts.assign(cells.begin(), cells.begin() + n);
    goals.resize(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) new_goal(i, starts[i]);
  }
  void new_goal(int i, Vertex from)
  {
    goals[i] = test::random_goal(g, comp, rng, from);
  }
};

}  // namespace

TEST(Wppl, EveryLifelongStepIsAValidLorrJointActionAndLnsNeverWorsensTheWindow)
{
  // 30 robots on a 12 x 10 grid with 15 % obstacles (about 30 % of the free cells),
  // 300 steps, 30 LNS iterations per step (deterministic), several seeds and options.
  for (uint64_t seed = 0; seed < 4; ++seed) {
    DenseRun run(12, 10, 15, 30, seed);
    const int n = static_cast<int>(run.starts.size());
    WpplOptions opt;
    opt.window = seed % 2 ? 8 : 15;
    opt.neighbourhood = seed < 2 ? 4 : 8;
    opt.reuse_tail = seed != 3;
    opt.accept_ties = seed != 2;
    Wppl p(run.g, run.starts, run.goals, seed, {}, 0, opt);
    p.set_back_last(seed % 2 == 1);
    long arrivals = 0, forwards = 0, turns = 0, improved = 0;
    for (int t = 1; t <= 300; ++t) {
      const Config cur = p.current();
      const std::vector<int> heads = p.headings();
      p.search(planner::Budget::expansion_count(30));
      const Config next = p.next();
      ASSERT_EQ(planner::Validator::check_transition(run.g, cur, next), "") << "seed " << seed << " step " << t;
      ASSERT_EQ(check_window(run.g, p.dist(), p.plan()), "") << "seed " << seed << " step " << t;
      // The objective is the sum of the windowed costs, and LNS only ever lowers it.
      int64_t sum = 0;
      for (int i = 0; i < n; ++i)
        sum += planner::windowed_cost(p.dist(), const_cast<RotationDist&>(p.dist()).table(run.goals[i]), run.goals[i], p.plan()[i]);
      ASSERT_EQ(sum, p.objective());
      ASSERT_LE(p.objective(), p.initial_objective()) << "seed " << seed << " step " << t;
      improved += p.objective() < p.initial_objective();
      const std::string acts = p.actions();
      p.commit();
      ASSERT_EQ(check_actions(p.dist(), acts, cur, heads, p.current(), p.headings()), "") << "seed " << seed << " step " << t;
      ASSERT_EQ(p.current(), next);
      for (char a : acts) forwards += a == 'F', turns += a == 'R' || a == 'C';
      bool changed = false;
      for (int i = 0; i < n; ++i)
        if (p.current()[i] == run.goals[i]) ++arrivals, run.new_goal(i, run.goals[i]), changed = true;
      if (changed) p.set_goals(run.goals);
    }
    EXPECT_GT(arrivals, 100) << "seed " << seed;
    EXPECT_GT(improved, 30) << "seed " << seed;  // LNS did work
    EXPECT_GT(p.lns_accepted(), 0u);
    EXPECT_GT(forwards, 0);
    EXPECT_GT(turns, 0);
    if (opt.reuse_tail) EXPECT_GT(p.tail_starts(), 0u) << "seed " << seed;
    else EXPECT_EQ(p.tail_starts(), 0u);
    if (opt.accept_ties) EXPECT_GT(p.lns_sideways(), 0u) << "seed " << seed;
    else EXPECT_EQ(p.lns_sideways(), 0u);
  }
}

TEST(Wppl, SidewaysMovesKeepTheObjectiveAndChangeTheWindow)
{
  // One LNS iteration at a time (search() goes on with the same window until commit()): the
  // objective never rises; an iteration accepted at equal cost (accept_ties, the default)
  // leaves it unchanged and, in some, replaces paths by other conflict-free ones.
  DenseRun run(12, 10, 15, 30, 7);
  Wppl p(run.g, run.starts, run.goals, 7);
  ASSERT_TRUE(p.options().accept_ties);
  int changed_windows = 0;
  for (int t = 1; t <= 60; ++t) {
    p.search(planner::Budget::expansion_count(0));
    for (int k = 0; k < 40; ++k) {
      const int64_t before = p.objective();
      const uint64_t sideways = p.lns_sideways();
      const std::vector<RotPath> window = p.plan();
      p.search(planner::Budget::expansion_count(1));
      ASSERT_LE(p.objective(), before) << "step " << t;
      if (p.lns_sideways() > sideways) {
        ASSERT_EQ(p.objective(), before);
        ASSERT_EQ(check_window(run.g, p.dist(), p.plan()), "") << "step " << t;
        changed_windows += !(p.plan() == window);
      }
    }
    p.commit();
    bool changed = false;
    for (int i = 0; i < static_cast<int>(run.goals.size()); ++i)
      if (p.current()[i] == run.goals[i]) run.new_goal(i, run.goals[i]), changed = true;
    if (changed) p.set_goals(run.goals);
  }
  EXPECT_GT(changed_windows, 10);
}

TEST(Wppl, WithoutLnsItTakesPibtRotsSteps)
{
  for (uint64_t seed = 0; seed < 3; ++seed) {
    DenseRun run(12, 10, 15, 30, seed);
    DenseRun run2(12, 10, 15, 30, seed);  // the same goal sequence for the second planner
    WpplOptions opt;
    opt.reuse_tail = false;
    Wppl w(run.g, run.starts, run.goals, seed, {}, 0, opt);
    planner::RotationPibt r(run2.g, run2.starts, run2.goals, seed);
    for (int t = 1; t <= 150; ++t) {
      w.search(planner::Budget::expansion_count(0));
      r.search(planner::Budget{});
      ASSERT_EQ(w.actions(), r.actions()) << "seed " << seed << " step " << t;
      w.commit();
      r.commit();
      bool changed = false;
      for (int i = 0; i < static_cast<int>(run.goals.size()); ++i)
        if (w.current()[i] == run.goals[i]) run.new_goal(i, run.goals[i]), run2.new_goal(i, run2.goals[i]), changed = true;
      if (changed) w.set_goals(run.goals), r.set_goals(run2.goals);
    }
  }
}

// Foreign pockets reach wppl's rollout (Wppl::set_pockets; RotationPibt's test
// AForeignPocketIsTheLastResortOfAPushedRobot): robot 1 on its goal above a one-cell dead end,
// facing into it, is asked to vacate by robot 0. Without pockets it drives into the stub;
// with the stub a pocket that is not its goal's it turns west instead. LNS on (the default
// iterations): it keeps the rollout's step, which is already optimal for the window.
TEST(Wppl, AForeignPocketIsTheLastResortOfAPushedRobot)
{
  const Graph g = test::grid({".....", "@@.@@"});
  const Vertex stub = g.at(2, 1), mouth = g.at(2, 0);
  for (uint64_t iters : {0, 20}) {
    auto step = [&](bool pockets) {
      Wppl w(g, {g.at(3, 0), mouth}, {g.at(0, 0), mouth}, 0);
      w.set_headings({2, 1});  // robot 0 west, robot 1 south (facing the stub)
      if (pockets) w.set_pockets(test::pocket_labels(g, {stub}, stub), 100.0f);
      w.search(planner::Budget::expansion_count(iters));
      return std::make_pair(w.actions(), w.next());
    };
    const auto [a_off, n_off] = step(false);
    EXPECT_EQ(n_off[1], stub) << a_off << " iters " << iters;  // into the stub
    const auto [a_on, n_on] = step(true);
    EXPECT_EQ(n_on[1], mouth) << a_on << " iters " << iters;   // stays out: turns
  }
}

TEST(Wppl, SameSeedAndIterationBudgetGiveTheSameSteps)
{
  DenseRun a(10, 10, 10, 25, 5), b(10, 10, 10, 25, 5);
  Wppl p(a.g, a.starts, a.goals, 5), q(b.g, b.starts, b.goals, 5);
  for (int t = 1; t <= 100; ++t) {
    p.search(planner::Budget::expansion_count(20));
    q.search(planner::Budget::expansion_count(20));
    ASSERT_EQ(p.actions(), q.actions()) << "step " << t;
    ASSERT_EQ(p.objective(), q.objective());
    p.commit();
    q.commit();
    bool changed = false;
    for (int i = 0; i < 25; ++i)
      if (p.current()[i] == a.goals[i]) a.new_goal(i, a.goals[i]), b.new_goal(i, b.goals[i]), changed = true;
    if (changed) p.set_goals(a.goals), q.set_goals(b.goals);
  }
  EXPECT_GT(p.lns_iterations(), 0u);
}

TEST(Wppl, LoneRobotReachesItsGoalInTheRotationShortestNumberOfSteps)
{
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const Graph g = random_grid(9, 7, 20, seed + 10);
    RotationDist d(g);
    planner::Rng rng(seed);
    for (int trial = 0; trial < 5; ++trial) {
      const Vertex s = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      const Vertex goal = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      const uint16_t want = d.get(d.table(goal), s, 0);
      if (want == RotationDist::kInf) continue;
      Wppl p(g, {s}, {goal}, seed);
      int steps = 0;
      while (!p.at_goal() && steps < 200) {
        p.search(planner::Budget::expansion_count(5));
        p.commit();
        ++steps;
      }
      EXPECT_EQ(steps, want) << "seed " << seed << " from " << s << " to " << goal;
    }
  }
}

TEST(Wppl, BadOptionsAreRefused)
{
  const Graph g = test::grid({"..."});
  WpplOptions opt;
  opt.window = 0;
  EXPECT_THROW(Wppl(g, {0}, {2}, 0, {}, 0, opt), std::invalid_argument);
  opt.window = 4;
  opt.neighbourhood = 0;
  EXPECT_THROW(Wppl(g, {0}, {2}, 0, {}, 0, opt), std::invalid_argument);
  EXPECT_THROW(Wppl(g, {0, 0}, {1, 2}), std::invalid_argument);  // RotationPibt's checks
}
