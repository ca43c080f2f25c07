// GraphExecution: RT-LaCAM + ADG (and lockstep) on MAPF graphs under random delays. The
// executed timeline is validated every tick (vertex / swap / adjacency), no two agents
// ever claim one cell (a moving agent claims both ends), and everything finishes.
#include <gtest/gtest.h>

#include <set>

#include "executor/graph_execution.hpp"
#include "grid.hpp"
#include "planner/movingai.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/validator.hpp"

using namespace executor;

namespace {

struct Outcome {
  bool finished = false;
  ExecStats stats;
  long long stop_ticks = 0;
};

// Runs to the goals (or max_ticks), checking the executed timeline every tick.
Outcome run(const planner::Graph& g, const planner::Instance& ins, const DelaySpec& d, const ExecOptions& o,
            long long max_ticks)
{
  planner::RtLacam p(g, ins.starts, ins.goals);
  GraphExecution ex(p, d, o);
  planner::Validator val(g, ins.starts, ins.goals);
  const planner::Budget b = planner::Budget::expansion_count(1);  // one expansion per call (a 0 ms budget now pauses it: resumable)
  Outcome out;
  for (long long t = 0; t < max_ticks && !ex.finished(); ++t) {
    ex.tick(b);
    EXPECT_TRUE(val.step(ex.positions())) << "tick " << t << ": " << val.error();
    if (!val.ok()) break;
    if (o.mode == "adg") {
      std::set<planner::Vertex> claimed;
      bool overlap = false;
      for (int i = 0; i < ins.num_agents(); ++i) {
        const int id = ex.adg().next_action(i);
        overlap |= !claimed.insert(ex.positions()[i]).second;
        if (id >= 0 && ex.adg().action(id).state == State::Running) overlap |= !claimed.insert(ex.adg().action(id).to).second;
      }
      EXPECT_FALSE(overlap) << "tick " << t << ": two agents claim one cell";
      if (overlap) break;
    }
  }
  out.finished = ex.finished();
  if (out.finished) {
    EXPECT_EQ(ex.positions(), ins.goals);
  }
  out.stats = ex.stats();
  out.stop_ticks = ex.delays().stop_ticks();
  return out;
}

// Bernoulli stops of 1..max_ticks ticks, probability p per agent per tick.
DelaySpec bernoulli_stops(double p, int max_ticks, uint64_t seed)
{
  DelaySpec d;
  d.kind = "bernoulli";
  d.p = p;
  d.min_ticks = 1;
  d.max_ticks = max_ticks;
  d.seed = seed;
  return d;
}

}  // namespace

TEST(GraphExecution, AdgUnderRandomDelaysNeverConflictsAndFinishes)
{
  const planner::Graph g = planner::load_map(RTLACAM_MOVINGAI "/random-32-32-20.map");
  const planner::Instance ins = planner::load_scen(RTLACAM_MOVINGAI "/random-32-32-20-random-1.scen", g, 100);
  for (uint64_t seed = 0; seed < 4; ++seed) {
    DelaySpec d = bernoulli_stops(0.05, 10, seed);
    d.slow = {{0, 0.3}, {1, 0.7}};
    ExecOptions o;
    o.window = 1 + static_cast<int>(seed) * 3;
    const Outcome r = run(g, ins, d, o, 5000);
    EXPECT_TRUE(r.finished) << "seed " << seed;
    EXPECT_GT(r.stop_ticks, 0);
    EXPECT_GT(r.stats.dependency_waits, 0);  // delays propagate through hand-overs
  }
}

TEST(GraphExecution, AdgSurvivesALongStuckAgentInACorridor)
{
  const planner::Graph g = planner::load_map(RTLACAM_MOVINGAI "/warehouse-10-20-10-2-1.map");
  const planner::Instance ins = planner::load_scen(RTLACAM_MOVINGAI "/warehouse-10-20-10-2-1-random-1.scen", g, 200);
  DelaySpec d;
  d.stuck = {{0, 5, 200}, {1, 0, 100}};
  ExecOptions o;
  o.window = 4;
  const Outcome r = run(g, ins, d, o, 5000);
  EXPECT_TRUE(r.finished);
  EXPECT_GE(r.stop_ticks, 300);
}

TEST(GraphExecution, WithoutDelaysLockstepExecutesThePlanOneToOne)
{
  const planner::Graph g = planner::load_map(RTLACAM_MOVINGAI "/random-32-32-20.map");
  const planner::Instance ins = planner::load_scen(RTLACAM_MOVINGAI "/random-32-32-20-random-1.scen", g, 50);
  ExecOptions o;
  o.mode = "lockstep";
  const Outcome r = run(g, ins, DelaySpec{}, o, 5000);
  EXPECT_TRUE(r.finished);
  EXPECT_EQ(r.stats.ticks, r.stats.commits);  // one committed configuration per tick
  EXPECT_EQ(r.stats.lockstep_waits, 0);
}

TEST(GraphExecution, LockstepWaitsForTheSlowestAdgDoesNot)
{
  const planner::Graph g = planner::load_map(RTLACAM_MOVINGAI "/random-32-32-20.map");
  const planner::Instance ins = planner::load_scen(RTLACAM_MOVINGAI "/random-32-32-20-random-1.scen", g, 50);
  const DelaySpec d = bernoulli_stops(0.02, 5, 7);
  ExecOptions lock, adg;
  lock.mode = "lockstep";
  adg.window = 8;
  const Outcome a = run(g, ins, d, lock, 20000), b = run(g, ins, d, adg, 20000);
  ASSERT_TRUE(a.finished);
  ASSERT_TRUE(b.finished);
  EXPECT_GT(a.stats.lockstep_waits, 0);
  EXPECT_LT(b.stats.ticks, a.stats.ticks);
}

TEST(GraphExecution, FollowingRuleIsValidUnderDelaysAndFasterThanHonigs)
{
  // adg-follow: a follower starts when its leader starts leaving, arrives only after it.
  // The timeline is validated every tick by run() (vertex / swap / adjacency): with slow
  // agents (2 ticks a move) a fast follower must wait at the door of the leader's cell.
  const planner::Graph g = planner::load_map(RTLACAM_MOVINGAI "/random-32-32-20.map");
  const planner::Instance ins = planner::load_scen(RTLACAM_MOVINGAI "/random-32-32-20-random-1.scen", g, 50);
  DelaySpec d = bernoulli_stops(0.02, 5, 7);
  for (int i = 0; i < 50; i += 5) d.slow.push_back({i, 0.5});
  ExecOptions honig, follow;
  honig.window = follow.window = 8;
  follow.mode = "adg-follow";
  const Outcome a = run(g, ins, d, honig, 20000), b = run(g, ins, d, follow, 20000);
  ASSERT_TRUE(a.finished);
  ASSERT_TRUE(b.finished);
  EXPECT_LT(b.stats.ticks, a.stats.ticks);
  // Without delays a train moves together: as fast as lockstep (one commit per tick).
  const Outcome c = run(g, ins, DelaySpec{}, follow, 5000);
  ASSERT_TRUE(c.finished);
  EXPECT_LE(c.stats.ticks, c.stats.commits + follow.window);
}

TEST(GraphExecution, CheckRejectsBadOptions)
{
  ExecOptions o;
  EXPECT_EQ(check(o), "");
  o.window = 0;
  EXPECT_EQ(check(o).rfind("window: ", 0), 0u);
  o = {};
  o.mode = "async";
  EXPECT_EQ(check(o).rfind("executor: ", 0), 0u);
}

TEST(GraphExecution, RotationWithASlowMemberMovesAsOne)
{
  // A 2x2 block; four agents rotate once, agent 0 at half speed: all four arrive together.
  const planner::Graph g = test::grid({"..", ".."});
  // Vertices: 0 (0,0) 1 (1,0) 2 (0,1) 3 (1,1); clockwise 0->1->3->2->0.
  struct Script : planner::RealtimePlanner {
    std::vector<planner::Config> s{{0, 1, 3, 2}, {1, 3, 2, 0}};
    size_t k = 0;
    planner::Config goals_{1, 3, 2, 0};
    planner::Status search(const planner::Budget&) override { return planner::Status::Searching; }
    const planner::Config& next() override { return s[std::min(k + 1, s.size() - 1)]; }
    void commit() override { k = std::min(k + 1, s.size() - 1); }
    void set_goals(const planner::Config&, planner::GoalTest) override {}
    const planner::Config& current() const override { return s[k]; }
    const planner::Config& goals() const override { return goals_; }
    bool at_goal() const override { return k + 1 == s.size(); }
    uint64_t expansions() const override { return 0; }
    size_t explored() const override { return 0; }
    std::string name() const override { return "script"; }
  } p;
  DelaySpec d;
  d.slow = {{0, 0.5}};
  GraphExecution ex(p, d, ExecOptions{});
  planner::Validator val(g, {0, 1, 3, 2}, {1, 3, 2, 0});
  ex.tick({0, 1});
  EXPECT_EQ(ex.positions(), (planner::Config{0, 1, 3, 2}));  // nobody arrived after one tick
  EXPECT_TRUE(val.step(ex.positions()));
  ex.tick({0, 1});
  EXPECT_EQ(ex.positions(), (planner::Config{1, 3, 2, 0}));
  EXPECT_TRUE(val.step(ex.positions())) << val.error();
  EXPECT_TRUE(ex.finished());
}
