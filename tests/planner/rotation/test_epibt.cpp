// EPIBT (solver epibt): the paper's operation set, a lone robot's shortest rotation path,
// LoRR-valid joint actions (cells: Validator; actions: replayed as MAPF_T) over dense
// lifelong runs with several seeds and every option, and a step cut short by its deadline.
#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <set>
#include <string>
#include <vector>

#include "planner/rotation/epibt.hpp"
#include "planner/rng.hpp"
#include "planner/rotation/rotation_dist.hpp"
#include "planner/validator.hpp"
#include "grid.hpp"

using planner::Config;
using planner::Epibt;
using planner::Graph;
using planner::RotationDist;
using planner::Vertex;

namespace {

using test::random_grid;

// Brute force: forward BFS over (cell, heading) with the MAPF_T moves from (v, o) until a
// state on `goal`; kInf when none is reachable.
int brute(const Graph& g, Vertex v, int o, Vertex goal)
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
    if (u == goal) return d[static_cast<size_t>(s)];
    const Vertex f = g.at(g.cell_x(u) + dx[h], g.cell_y(u) + dy[h]);
    for (int n : {f >= 0 ? f * 4 + h : -1, u * 4 + (h + 1) % 4, u * 4 + (h + 3) % 4})
      if (n >= 0 && d[static_cast<size_t>(n)] < 0) {
        d[static_cast<size_t>(n)] = d[static_cast<size_t>(s)] + 1;
        q.push_back(n);
      }
  }
  return RotationDist::kInf;
}

// One MAPF_T step as LoRR applies it to (cur, heads) with `acts`; "" when it gives (next, next_heads).
std::string replay(const Graph& g, const Config& cur, const std::vector<int>& heads, const std::string& acts,
                   const Config& next, const std::vector<int>& next_heads)
{
  static const int dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
  for (size_t i = 0; i < cur.size(); ++i) {
    Vertex v = cur[i];
    int h = heads[i];
    if (acts[i] == 'F') v = g.at(g.cell_x(v) + dx[h], g.cell_y(v) + dy[h]);
    else if (acts[i] == 'R') h = (h + 1) % 4;
    else if (acts[i] == 'C') h = (h + 3) % 4;
    else if (acts[i] != 'W') return "unknown action";
    if (v < 0) return "agent " + std::to_string(i) + " forward into a wall";
    if (v != next[i] || h != next_heads[i]) return "agent " + std::to_string(i) + " action " + acts[i] + " mismatch";
  }
  return "";
}

}  // namespace

TEST(Epibt, TheOperationSetOfDepth3IsThePapers17)
{
  const std::vector<std::string> ops = Epibt::operations(3);
  const std::set<std::string> got(ops.begin(), ops.end());
  const std::set<std::string> want = {"WWW", "RRF", "RWF", "CWF", "WWF", "RFW", "CFW", "WFW", "RFF",
                                      "CFF", "FWW", "WFF", "FRF", "FCF", "FWF", "FFW", "FFF"};
  EXPECT_EQ(got, want);
  EXPECT_EQ(ops.size(), 17u);
  EXPECT_EQ(ops.front(), "FFF");  // forward earliest first
  EXPECT_EQ(ops.back(), "WWW");
  EXPECT_EQ(Epibt::operations(4).size(), 48u);  // the paper's depth-4 and depth-5 sets
  EXPECT_EQ(Epibt::operations(5).size(), 136u);
  EXPECT_THROW(Epibt::operations(2), std::invalid_argument);  // no half turn: stuck in dead ends
  EXPECT_THROW(Epibt::operations(6), std::invalid_argument);
}

TEST(Epibt, LoneRobotReachesItsGoalInTheRotationShortestNumberOfSteps)
{
  int checked = 0;
  for (uint64_t seed = 0; seed < 6; ++seed) {
    const Graph g = random_grid(9, 7, 20, seed + 10);
    planner::Rng rng(seed);
    for (int trial = 0; trial < 8; ++trial) {
      const Vertex s = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      const Vertex goal = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
      const int want = brute(g, s, 0, goal);  // robots start facing east
      if (want == RotationDist::kInf) continue;
      for (int depth : {3, 4, 5}) {
        planner::EpibtOptions opt;
        opt.depth = depth;
        Epibt p(g, {s}, {goal}, opt);
        int steps = 0;
        while (!p.at_goal() && steps < 200) {
          p.search(planner::Budget{});
          p.commit();
          ++steps;
        }
        EXPECT_EQ(steps, want) << "seed " << seed << " depth " << depth << " from " << s << " to " << goal;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(Epibt, ARobotOnItsGoalStaysThere)
{
  const Graph g = test::grid({"....", "...."});
  Epibt p(g, {g.at(1, 0), g.at(3, 1)}, {g.at(1, 0), g.at(0, 1)});
  for (int t = 0; t < 12; ++t) {
    p.search(planner::Budget{});
    p.commit();
  }
  EXPECT_TRUE(p.at_goal());
  EXPECT_EQ(p.current()[0], g.at(1, 0));
}

TEST(Epibt, EveryLifelongStepIsAValidLorrJointActionAndRobotsArrive)
{
  // 30 robots on a 12 x 10 grid with 15 % obstacles (about 30 % of the free cells), new
  // random goals on arrival, 300 steps, several seeds, each option.
  struct Variant {
    const char* name;
    planner::EpibtOptions opt;
  };
  std::vector<Variant> variants(8);
  variants[0].name = "default (lns 20)";
  for (size_t k = 1; k < variants.size(); ++k) variants[k].opt.lns_rounds = 0;  // plain EPIBT
  variants[1].name = "no lns (the paper's EPIBT)";
  variants[2].name = "age", variants[2].opt.priority = planner::EpibtOptions::Priority::Age;
  variants[3].name = "wait-op", variants[3].opt.wait_op = true;
  variants[4].name = "no-inherit", variants[4].opt.inherit = false;
  variants[5].name = "depth 5", variants[5].opt.depth = 5;
  variants[6].name = "depth 4, revisit 2", variants[6].opt.depth = 4, variants[6].opt.revisit = 2;
  variants[7].name = "lns 4 converge, age", variants[7].opt.lns_rounds = 4, variants[7].opt.lns_converge = true,
  variants[7].opt.priority = planner::EpibtOptions::Priority::Age;
  for (const Variant& var : variants)
    for (uint64_t seed = 0; seed < 4; ++seed) {
      const Graph g = random_grid(12, 10, 15, seed + 100);
      std::vector<int> comp_id = g.components();
      planner::Rng rng(seed);
      std::vector<Vertex> free_cells;
      for (Vertex v = 0; v < g.size(); ++v) free_cells.push_back(v);
      rng.shuffle(free_cells.data(), static_cast<int>(free_cells.size()));
      const int n = 30;
      Config starts(free_cells.begin(), free_cells.begin() + n), goals(static_cast<size_t>(n));
      auto new_goal = [&](int i, Vertex from) {  // a reachable cell other than `from`
        for (;;) {
          const Vertex v = static_cast<Vertex>(rng.below(static_cast<uint32_t>(g.size())));
          if (v != from && comp_id[v] == comp_id[from]) return goals[i] = v;
        }
      };
      for (int i = 0; i < n; ++i) new_goal(i, starts[i]);
      planner::EpibtOptions opt = var.opt;
      opt.seed = seed;  // LNS order
      Epibt p(g, starts, goals, opt);
      long arrivals = 0, forwards = 0, turns = 0;
      for (int t = 1; t <= 300; ++t) {
        const Config cur = p.current();
        const std::vector<int> heads = p.headings();
        p.search(planner::Budget{});
        const Config next = p.next();
        ASSERT_EQ(planner::Validator::check_transition(g, cur, next), "") << var.name << " seed " << seed << " step " << t;
        const std::string acts = p.actions();
        for (int i = 0; i < n; ++i) ASSERT_EQ(acts[i], p.operation(i)[0]) << "the first action of its operation";
        p.commit();
        ASSERT_EQ(replay(g, cur, heads, acts, p.current(), p.headings()), "") << var.name << " seed " << seed << " step " << t;
        ASSERT_EQ(p.current(), next);
        for (char a : acts) forwards += a == 'F', turns += a == 'R' || a == 'C';
        bool changed = false;
        for (int i = 0; i < n; ++i)
          if (p.current()[i] == goals[i]) ++arrivals, new_goal(i, goals[i]), changed = true;
        if (changed) p.set_goals(goals);
      }
      EXPECT_GT(arrivals, 50) << var.name << " seed " << seed;
      EXPECT_GT(forwards, 0);
      EXPECT_GT(turns, 0);
      EXPECT_EQ(p.timeouts(), 0u);
    }
}

TEST(Epibt, AStepCutShortByItsDeadlineIsStillValid)
{
  // A 0 ms budget: replanning stops at once; robots keep their inherited operations.
  const Graph g = random_grid(16, 16, 10, 7);
  planner::Rng rng(3);
  const std::vector<Vertex> cells = test::shuffled_cells(g, rng);
  const Config starts(cells.begin(), cells.begin() + 60), goals(cells.begin() + 60, cells.begin() + 120);
  Epibt p(g, starts, goals);
  for (int t = 0; t < 40; ++t) {
    const Config cur = p.current();
    p.search(t % 2 ? planner::Budget::time_ms(0) : planner::Budget{});
    ASSERT_EQ(planner::Validator::check_transition(g, cur, p.next()), "") << "step " << t;
    p.commit();
  }
  EXPECT_GT(p.timeouts(), 0u);
  EXPECT_LE(p.timeouts(), 20u);
}

// Foreign pockets (Epibt::set_pockets, tasks.urgency.pocket_cost; RotationPibt's rule):
// robot 1 stands on its goal in a corridor above a one-cell dead end, facing south into it;
// robot 0 (west-bound, older: it goes first) drives FFF through robot 1's cell. Robot 1 must
// leave: into the stub (FWW: 3 actions + 3 back to its goal) or ahead of robot 0 (RFF: 3 + 4).
// Without pockets it takes the stub; with the stub a pocket that is not its goal's, RFF. Bound
// for the stub, its own pocket costs nothing.
TEST(Epibt, AForeignPocketIsTheLastResortOfAPushedRobot)
{
  const Graph g = test::grid({".....", "@@.@@"});
  const Vertex stub = g.at(2, 1), mouth = g.at(2, 0);
  for (int rounds : {0, 20}) {
    auto op = [&](bool pockets, Vertex goal1) {
      planner::EpibtOptions opt;
      opt.priority = planner::EpibtOptions::Priority::Age;
      opt.lns_rounds = rounds;
      Epibt p(g, {g.at(4, 0), mouth}, {g.at(0, 0), goal1}, opt);
      p.set_headings({2, 1});  // robot 0 west, robot 1 south (facing the stub)
      if (pockets) p.set_pockets(test::pocket_labels(g, {stub}, stub), 100.0f);
      p.search(planner::Budget{});
      return std::make_pair(p.operation(0), p.operation(1));
    };
    EXPECT_EQ(op(false, mouth), std::make_pair(std::string("FFF"), std::string("FWW"))) << "rounds " << rounds;
    EXPECT_EQ(op(true, mouth), std::make_pair(std::string("FFF"), std::string("RFF"))) << "rounds " << rounds;
    EXPECT_EQ(op(true, stub).second[0], 'F') << "rounds " << rounds;  // bound for the stub: drives in
  }
}

// The pocket exit rule (EpibtOptions::pocket_exit): a one-wide stub of two cells under a
// corridor; robot 0 holds the station at the stub's end, facing the wall, its new goal at the
// corridor's west end; robot 1, at the mouth facing the stub, is the next holder. By the
// paper's priority (nearest first) robot 1 plans first, cannot take the station cell (robot 0
// needs three actions to leave it) and drives into the stub: robot 0 is walled in behind it
// and neither moves again (the trap behind the collapse of the warehouse twins, s36). With
// the rule robot 1 stays out while robot 0 is in the stub, robot 0 leaves, then robot 1 enters.
TEST(Epibt, NobodyGoesDeeperIntoAPocketThatARobotMustLeave)
{
  const Graph g = test::grid({"@@.@@", "@@.@@", "....."});
  const Vertex station = g.at(2, 0), inner = g.at(2, 1), mouth = g.at(2, 2);
  const std::vector<Vertex> pocket = test::pocket_labels(g, {station, inner}, station);
  for (int rounds : {0, 20})
    for (bool rule : {false, true}) {
      planner::EpibtOptions opt;
      opt.lns_rounds = rounds;
      opt.pocket_exit = rule;
      Epibt p(g, {station, mouth}, {g.at(0, 2), station}, opt);
      p.set_headings({3, 3});  // both face north: robot 0 the wall, robot 1 the stub
      p.set_pockets(pocket, 0.0f);  // labels only: no foreign-pocket cost
      p.search(planner::Budget{});
      EXPECT_EQ(p.next()[1] == inner, !rule) << "rounds " << rounds << " rule " << rule;
      int out = -1, in = -1;  // steps until robot 0 is out of the stub, robot 1 on the station
      for (int t = 1; t <= 20; ++t) {
        p.commit();
        p.search(planner::Budget{});
        if (out < 0 && pocket[static_cast<size_t>(p.current()[0])] < 0) out = t;
        if (in < 0 && p.current()[1] == station) in = t;
      }
      if (rule) {
        EXPECT_GT(out, 0) << "rounds " << rounds;
        EXPECT_GT(in, out) << "rounds " << rounds;
      } else {
        EXPECT_EQ(out, -1) << "rounds " << rounds;  // walled in: the trap
      }
    }
}

// Two lines meet head-on in a one-wide corridor between two open halls: `down` robots facing
// south bound for the lower hall, `up` robots facing north bound for the upper one. One line
// must back out of the corridor; each robot of it needs two turns before it can move, so the
// chain of operations that makes way ("RRF" down the line, "WWF" for the robot facing it) is
// found only after the root's earlier candidates (FFF, FFW, WFF, ...) have failed, each of them
// replanning the whole line again. With the paper's 10 replans per robot per step the line's
// robots run out before the working chain is tried and the lines face each other for ever
// (the 1000-AGV warehouse's picking aisles, docs/twin_bench.md "Session 40"); with the
// default both halls fill.
TEST(Epibt, ALineBacksOutOfACorridorForALineFacingIt)
{
  struct Case {
    int down, up, length;
  };
  for (const Case c : {Case{5, 5, 10}, Case{3, 1, 10}, Case{6, 2, 12}, Case{8, 8, 20}})
    for (int revisit : {10, planner::EpibtOptions{}.revisit}) {
      std::vector<std::string> rows(3, "........");
      rows.insert(rows.end(), static_cast<size_t>(c.length), "@@@.@@@@");
      rows.insert(rows.end(), 3, "........");
      const Graph g = test::grid(rows);
      Config starts, goals;
      std::vector<int> heads;
      for (int k = 0; k < c.down; ++k)
        starts.push_back(g.at(3, 3 + k)), goals.push_back(g.at((2 * k) % 8, c.length + 5 - k / 4)), heads.push_back(1);
      for (int k = 0; k < c.up; ++k)
        starts.push_back(g.at(3, c.down + 3 + k)), goals.push_back(g.at(7 - (2 * k) % 8, k / 4)), heads.push_back(3);
      planner::EpibtOptions opt;
      opt.priority = planner::EpibtOptions::Priority::Age;  // the warehouse configs' (controller: planner.rotation.priority)
      opt.revisit = revisit;
      Epibt p(g, starts, goals, opt);
      p.set_headings(heads);
      int t = 0;
      for (; t < 300 && !p.at_goal(); ++t) {
        const Config cur = p.current();
        p.search(planner::Budget{});
        ASSERT_EQ(planner::Validator::check_transition(g, cur, p.next()), "");
        p.commit();
      }
      const std::string what = std::to_string(c.down) + " down, " + std::to_string(c.up) + " up, corridor " +
                               std::to_string(c.length) + ", revisit " + std::to_string(revisit);
      if (revisit == 10) {
        EXPECT_FALSE(p.at_goal()) << what << ": the paper's limit no longer jams here";
      } else {
        EXPECT_TRUE(p.at_goal()) << what;
        EXPECT_LT(t, 4 * (c.length + 8)) << what;  // a few corridor lengths, not a crawl
      }
    }
}

TEST(Epibt, BadInputIsRefused)
{
  const Graph line = Graph::from_edges(2, {{0, 1}});
  EXPECT_THROW(Epibt(line, {0}, {1}), std::invalid_argument);
  const Graph g = test::grid({"..."});
  EXPECT_THROW(Epibt(g, {0, 0}, {1, 2}), std::invalid_argument);
  EXPECT_THROW(Epibt(g, {0}, {7}), std::invalid_argument);
  planner::EpibtOptions bad;
  bad.revisit = 0;
  EXPECT_THROW(Epibt(g, {0}, {1}, bad), std::invalid_argument);
}
