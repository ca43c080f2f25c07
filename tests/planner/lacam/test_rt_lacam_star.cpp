// RT-LaCAM* (LacamOptions::refine): the first solution comes from LaCAM's very search,
// g stays the tree-path cost through reroots, the followed path only gets cheaper, and
// with enough budget the cost is optimal (checked against Dijkstra over joint
// configurations).
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <map>
#include <queue>

#include "planner/lacam/lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/lacam/runner.hpp"
#include "planner/validator.hpp"
#include "drive_refined.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

struct Inst {
  std::string name;
  Graph g;
  Config s, t;
};

std::vector<Inst> tiny()
{
  std::vector<Inst> out;
  for (const auto& c : test::hard_cases()) {
    Graph g = test::grid(c.rows);
    out.push_back({c.name, g, test::at(g, c.starts), test::at(g, c.goals)});
  }
  Graph open = test::grid({"....", "....", "...."});
  out.push_back({"open3x4", open, test::at(open, {{0, 0}, {3, 2}, {3, 0}}), test::at(open, {{3, 2}, {0, 0}, {0, 2}})});
  return out;
}

// LaCAM*'s cost: per agent per action, 0 while staying on the goal.
int64_t edge_cost(const Config& a, const Config& b, const Config& goals)
{
  int64_t c = 0;
  for (size_t i = 0; i < a.size(); ++i) c += !(a[i] == goals[i] && b[i] == goals[i]);
  return c;
}

// Every joint move without vertex or swap conflicts, by enumeration.
void successors(const Graph& g, const Config& C, size_t i, Config& next, std::vector<Config>& out)
{
  if (i == C.size()) {
    for (size_t a = 0; a < C.size(); ++a)
      for (size_t b = a + 1; b < C.size(); ++b)
        if (next[a] == next[b] || (next[a] == C[b] && next[b] == C[a])) return;
    out.push_back(next);
    return;
  }
  std::vector<Vertex> moves{C[i]};
  for (Vertex u : g.neighbors(C[i])) moves.push_back(u);
  for (Vertex u : moves) {
    next[i] = u;
    successors(g, C, i + 1, next, out);
  }
}

// Exhaustive Dijkstra over joint configurations: the optimal LaCAM* cost.
int64_t optimal_cost(const Graph& g, const Config& s, const Config& t)
{
  std::map<Config, int64_t> dist{{s, 0}};
  using Item = std::pair<int64_t, Config>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
  pq.push({0, s});
  Config scratch(s.size());
  while (!pq.empty()) {
    auto [d, C] = pq.top();
    pq.pop();
    if (d > dist[C]) continue;
    if (C == t) return d;
    std::vector<Config> next;
    successors(g, C, 0, scratch, next);
    for (const Config& D : next) {
      const int64_t nd = d + edge_cost(C, D, t);
      auto it = dist.find(D);
      if (it == dist.end() || nd < it->second) {
        dist[D] = nd;
        pq.push({nd, D});
      }
    }
  }
  return -1;
}

// Cost of the tree path root -> goal, summed edge by edge (not read from g).
int64_t remaining_cost(const Lacam& l, const Config& goals)
{
  int64_t c = 0;
  const int n = l.num_agents();
  for (const HNode* h = l.goal_node(); h && h->parent; h = h->parent)
    c += edge_cost(Config(h->parent->C, h->parent->C + n), Config(h->C, h->C + n), goals);
  return c;
}

LacamOptions refine_opts(uint64_t seed)
{
  LacamOptions o;
  o.refine = true;
  o.seed = seed;
  return o;
}

}  // namespace

TEST(RtLacamStar, FullHorizonLacamStarReachesTheOptimum)
{
  for (const auto& in : tiny()) {
    const int64_t opt = optimal_cost(in.g, in.s, in.t);
    ASSERT_GT(opt, 0) << in.name;
    for (uint64_t seed = 0; seed < 4; ++seed) {
      SCOPED_TRACE(in.name + " seed " + std::to_string(seed));
      DistTable d(in.g);
      Lacam l(in.g, d, refine_opts(seed));
      l.reset(in.s, in.t);
      ASSERT_EQ(l.search(Budget::unlimited(), true), Status::Solved);
      const int64_t first = l.goal_node()->g;
      EXPECT_GE(first, opt);
      l.search(Budget::unlimited());
      EXPECT_FALSE(l.refining());
      EXPECT_FALSE(l.refine_capped());
      EXPECT_EQ(l.goal_node()->g, opt) << "first solution cost " << first;
      EXPECT_EQ(remaining_cost(l, in.t), opt);
      EXPECT_EQ(validate_plan(in.g, in.s, in.t, l.path(l.goal_node()), true), "");
    }
  }
}

TEST(RtLacamStar, RealTimeRunWithAmpleBudgetExecutesAnOptimalPath)
{
  for (const auto& in : tiny()) {
    const int64_t opt = optimal_cost(in.g, in.s, in.t);
    SCOPED_TRACE(in.name);
    RtLacam rt(in.g, in.s, in.t, refine_opts(1));
    Validator val(in.g, in.s, in.t);
    int64_t executed = 0;
    for (int k = 0; k < 1000 && !rt.at_goal(); ++k) {
      rt.search(Budget::expansion_count(1000000));
      const Config from = rt.current();
      rt.next();
      rt.commit();
      ASSERT_TRUE(val.step(rt.current())) << val.error();
      executed += edge_cost(from, rt.current(), in.t);
    }
    ASSERT_TRUE(rt.at_goal());
    EXPECT_EQ(executed, opt);
  }
}

TEST(RtLacamStar, GStaysTheTreePathCostThroughReroots)
{
  // Brute force after every move: g of every node equals the sum of edge costs along its
  // tree path from the current root (Lacam::check_costs), and the tree stays a tree.
  std::vector<Inst> ins = tiny();
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 30);
  ins.push_back({"random-32-32-20/30", g, r.starts, r.goals});
  for (const auto& in : ins) {
    for (uint64_t per_step : {1u, 5u, 40u}) {
      SCOPED_TRACE(in.name + " per_step " + std::to_string(per_step));
      RtLacam rt(in.g, in.s, in.t, refine_opts(per_step));
      Validator val(in.g, in.s, in.t);
      long checked = 0;
      for (int k = 0; k < 5000 && !rt.at_goal(); ++k) {
        rt.search(Budget::expansion_count(per_step));
        const Config promised = rt.next();
        rt.search(Budget::expansion_count(per_step));  // may re-parent the promised node
        rt.commit();
        ASSERT_EQ(rt.current(), promised);
        ASSERT_TRUE(val.step(rt.current())) << val.error();
        std::string why;
        ASSERT_TRUE(rt.lacam().check_tree(&why)) << why;
        if (rt.lacam().refining()) {
          ASSERT_TRUE(rt.lacam().check_costs(&why)) << "step " << k << ": " << why;
          ++checked;
        }
      }
      EXPECT_TRUE(rt.at_goal());
      if (per_step == 1) {
        EXPECT_GT(checked, 0) << "never checked a refining search";
      }
    }
  }
}

TEST(RtLacamStar, ACutRewiringResumesAndGReturnsToTheTreePathCost)
{
  // A rewiring after a known-node hit is cut (here after 1 node per step, the deterministic
  // stand-in for the deadline) and resumed by the next refinement steps: moves stay valid,
  // parents stay a tree, and once nothing is pending every g is the tree-path cost again.
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 30);
  LacamOptions o = refine_opts(5);
  o.rewire_slice = 1;
  RtLacam rt(g, r.starts, r.goals, o);
  Validator val(g, r.starts, r.goals);
  long pending = 0, checked_after = 0;
  bool was_pending = false;
  for (int k = 0; k < 5000 && !rt.at_goal(); ++k) {
    rt.search(Budget::expansion_count(5));
    rt.next();
    rt.commit();
    ASSERT_TRUE(val.step(rt.current())) << val.error();
    std::string why;
    ASSERT_TRUE(rt.lacam().check_tree(&why)) << why;
    if (rt.lacam().rewire_pending()) {
      ++pending;
      was_pending = true;
    } else if (rt.lacam().refining()) {
      ASSERT_TRUE(rt.lacam().check_costs(&why)) << "step " << k << ": " << why;
      checked_after += was_pending;
      was_pending = false;
    }
  }
  EXPECT_TRUE(rt.at_goal());
  EXPECT_GT(rt.lacam().rewire_cuts(), 0u);
  EXPECT_GT(pending, 0);
  EXPECT_GT(checked_after, 0) << "no g checked after a cut rewiring finished";
}

namespace {

// Runs RT-LaCAM* (20 expansions per move) to the goals: every move passes the validator and
// executed cost + the followed tree path's remaining cost, recomputed edge by edge, never rises
// (the loss objective, where the followed path is the goal's tree path; Objective::soc:
// test_objective.cpp).
void expect_followed_path_never_costlier(const Graph& g, const Instance& r, LacamOptions o)
{
  o.objective = Objective::loss;
  RtLacam rt(g, r.starts, r.goals, o);
  Validator val(g, r.starts, r.goals);
  int64_t executed = 0, best = -1, first = -1;
  for (int k = 0; k < 5000 && !rt.at_goal(); ++k) {
    rt.search(Budget::expansion_count(20));
    const Config from = rt.current();
    rt.next();
    rt.commit();
    ASSERT_TRUE(val.step(rt.current())) << val.error();
    executed += edge_cost(from, rt.current(), r.goals);
    if (!rt.lacam().goal_node()) continue;
    const int64_t total = executed + remaining_cost(rt.lacam(), r.goals);
    if (best >= 0) {
      ASSERT_LE(total, best) << "step " << k;
    }
    if (first < 0) first = total;
    best = total;
  }
  ASSERT_TRUE(rt.at_goal());
  EXPECT_EQ(executed, best);
  EXPECT_LE(best, first);
}

}  // namespace

TEST(RtLacamStar, TheFollowedPathNeverGetsCostlier)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  for (int n : {20, 60, 120}) {
    Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-2.scen", g, n);
    SCOPED_TRACE(n);
    expect_followed_path_never_costlier(g, r, refine_opts(0));
  }
}

TEST(RtLacamStar, EveryLnsNeighbourhoodKeepsTheFollowedPathValidAndNeverCostlier)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-2.scen", g, 80);
  for (auto nbh : {LnsNeighbourhood::blocking, LnsNeighbourhood::intersection, LnsNeighbourhood::adaptive}) {
    SCOPED_TRACE(static_cast<int>(nbh));
    LacamOptions o = refine_opts(1);
    o.lns_neighbourhood = nbh;
    expect_followed_path_never_costlier(g, r, o);
  }
}

TEST(RtLacamStar, FirstSolutionComesFromLacamsVerySearch)
{
  // With refine on, the search up to the first solution is LaCAM's: same expansions, same
  // explored set as full-horizon LaCAM without refine, and the same executed moves as the
  // paper's RT-LaCAM until then.
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  std::vector<Inst> ins = tiny();
  for (int n : {40, 150}) {
    Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-2.scen", g, n);
    ins.push_back({"random/" + std::to_string(n), g, r.starts, r.goals});
  }
  for (const auto& in : ins) {
    for (uint64_t seed = 0; seed < 3; ++seed) {
      SCOPED_TRACE(in.name + " seed " + std::to_string(seed));
      LacamOptions plain;
      plain.seed = seed;
      DistTable d(in.g);
      Lacam full(in.g, d, plain);
      full.reset(in.s, in.t);
      ASSERT_EQ(full.search(Budget::unlimited()), Status::Solved);

      RtLacam star(in.g, in.s, in.t, refine_opts(seed));
      RtLacam paper(in.g, in.s, in.t, plain);
      for (int k = 0; k < 100000 && !star.lacam().goal_node(); ++k) {
        star.step(Budget::expansion_count(3));
        paper.step(Budget::expansion_count(3));
        if (star.lacam().goal_node()) break;  // from here on the two may differ
        star.commit();
        paper.commit();
        ASSERT_EQ(star.current(), paper.current()) << "step " << k;
      }
      ASSERT_NE(star.lacam().goal_node(), nullptr);
      EXPECT_EQ(star.lacam().expansions_at_solution(), full.expansions());
      EXPECT_EQ(star.lacam().explored_at_solution(), full.explored());
    }
  }
}

TEST(RtLacamStar, RefineAfterSolveImprovesOrKeepsTheCostAndStaysValid)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 100);
  RunOptions ro;
  ro.record_plan = true;
  const RunResult first = run_full_horizon(g, r.starts, r.goals, refine_opts(0), ro);
  ro.anytime_ms = 300;
  const RunResult anytime = run_full_horizon(g, r.starts, r.goals, refine_opts(0), ro);
  ASSERT_TRUE(first.solved);
  ASSERT_TRUE(anytime.solved);
  EXPECT_EQ(validate_plan(g, r.starts, r.goals, anytime.plan, true), "");
  EXPECT_GE(anytime.total_planning_ms, 250);
  EXPECT_GT(anytime.expansions, first.expansions);
  auto cost = [&](const std::vector<Config>& p) {
    int64_t c = 0;
    for (size_t t = 1; t < p.size(); ++t) c += edge_cost(p[t - 1], p[t], r.goals);
    return c;
  };
  EXPECT_LE(cost(anytime.plan), cost(first.plan));
}

TEST(RtLacamStar, WallClockRunsAreValidAndTheMemoryCapHolds)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 150);
  for (size_t cap_mb : {size_t{512}, size_t{0}}) {
    LacamOptions o = refine_opts(0);
    o.refine_max_mb = cap_mb;
    RtLacam rt(g, r.starts, r.goals, o);
    RunOptions ro;
    ro.per_iteration = Budget::time_ms(0.5);
    RunResult res = run_realtime(rt, g, r.starts, r.goals, ro);
    EXPECT_TRUE(res.solved) << cap_mb;
    EXPECT_EQ(validate_plan(g, r.starts, r.goals, res.plan, true), "");
    if (cap_mb == 0) {
      EXPECT_TRUE(rt.lacam().refine_capped()) << "a 0 MB cap stops refinement at once";
    }
  }
}

TEST(RtLacamStar, AnExpansionsBudgetBoundsLnsWork)
{
  // An LNS step costs O(T x N), an expansion O(N): against a budget in expansions the step
  // is charged its work / N and what it overruns is paid by the next calls, which then do
  // nothing. Without LNS every call does exactly one LaCAM* expansion.
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 100);
  for (bool lns : {true, false}) {
    SCOPED_TRACE(lns ? "lns" : "no lns");
    DistTable dist(g);
    LacamOptions opt = refine_opts(0);
    opt.lns = lns;
    Lacam lc(g, dist, opt);
    lc.reset(r.starts, r.goals);
    ASSERT_EQ(lc.search(Budget{}, true), Status::Solved);
    int idle = 0, calls = 0;
    for (; calls < 400 && lc.refining(); ++calls) {
      const uint64_t e = lc.expansions();
      lc.search(Budget{std::numeric_limits<double>::infinity(), 1});
      const uint64_t done = lc.expansions() - e;
      EXPECT_LE(done, 1u);
      idle += done == 0;
    }
    ASSERT_GT(calls, 100);
    if (lns) EXPECT_GT(idle, calls / 2);  // each LNS step is worth >= T (> 20) expansions
    else EXPECT_EQ(idle, 0);
    std::string why;
    if (lc.refining()) {
      EXPECT_TRUE(lc.check_costs(&why)) << why;
    }
  }
}

TEST(RtLacamStar, RefinerThreadWindowsAreAdoptedValidAndNeverCostlier)
{
  // A refiner thread (LacamOptions::refine_threads, refine_thread.hpp) runs LNS on a copy of
  // the followed path; the search adopts its windows at its iteration boundaries. What is
  // asserted does not depend on timing: before each of the first iterations the test waits
  // for the worker to publish (or give up), so windows arrive however loaded the machine is;
  // the windows adopted are those still ahead of the executed configuration, each keeps the
  // followed path's standard SOC or lowers it (some lower it), and the executed plan is valid
  // and reaches the goals. With 0 threads nothing is adopted (and this test fails).
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  Instance r = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 120);
  LacamOptions o = refine_opts(0);
  o.refine_threads = 1;
  RtLacam rt(g, r.starts, r.goals, o);
  Validator v(g, r.starts, r.goals);
  const int steps = test::drive_refined(rt, v, 2000, 60);
  ASSERT_TRUE(rt.at_goal());
  const auto adopted = rt.lacam().thread_adoptions();
  std::printf("steps %d, posts %llu, worker improvements %llu, windows adopted %zu (cheaper %llu), refused %llu, "
              "executed SOC %lld\n",
              steps, static_cast<unsigned long long>(rt.lacam().thread_posts()),
              static_cast<unsigned long long>(rt.lacam().refiner_improvements()), adopted.size(),
              static_cast<unsigned long long>(rt.lacam().thread_wins()),
              static_cast<unsigned long long>(rt.lacam().thread_refused()), v.sum_of_costs());
  EXPECT_EQ(adopted.size(), rt.lacam().thread_windows());
  for (const auto& [before, after] : adopted) EXPECT_LE(after, before);
  EXPECT_GT(rt.lacam().thread_wins(), 0u);
}
