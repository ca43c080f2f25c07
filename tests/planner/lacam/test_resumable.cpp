// Resumable expansions (LacamOptions::resumable, Pibt::start/resume): an expansion paused
// at every chance gives LaCAM's very successor and tree, survives reroots, is dropped by
// reset() and restarted by set_immobile(), and bounds the work of one timed call.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "planner/lacam/lacam.hpp"
#include "planner/lacam/naive_rt_lacam.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/validator.hpp"
#include "test_util.hpp"

using namespace planner;

namespace {

struct Inst {
  std::string name;
  Graph g;
  Config s, t;
};

std::vector<Inst> instances()
{
  std::vector<Inst> out;
  for (const auto& c : test::hard_cases()) {
    Graph g = test::grid(c.rows);
    out.push_back({c.name, g, test::at(g, c.starts), test::at(g, c.goals)});
  }
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  Graph g = load_map(dir + "random-32-32-20.map");
  for (int n : {40, 120, 200}) {
    Instance ins = load_scen(dir + "random-32-32-20-random-2.scen", g, n);
    out.push_back({"random-32-32-20/" + std::to_string(n), g, ins.starts, ins.goals});
  }
  return out;
}

Inst big()
{
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  Graph g = load_map(dir + "random-32-32-20.map");
  Instance ins = load_scen(dir + "random-32-32-20-random-1.scen", g, 200);
  return {"random-32-32-20/200", g, ins.starts, ins.goals};
}

// A deadline that has always passed: resume() stops at its every chance.
const Clock::time_point kPast = Clock::time_point::min();

// Options under which a zero budget pauses expansions (no floor: LacamOptions::pause_min_ms).
LacamOptions pausing(LacamOptions o = {})
{
  o.pause_min_ms = 0;
  return o;
}

// Runs a generation to its end, pausing at every chance; returns the number of pieces.
int resume_in_pieces(Pibt& p, Rng& rng, Pibt::Gen* result)
{
  int pieces = 0;
  Pibt::Gen r;
  do {
    r = p.resume(rng, kPast);
    ++pieces;
  } while (r == Pibt::Gen::paused);
  *result = r;
  return pieces;
}

}  // namespace

// Successive PIBT steps of 200 agents under constraint chains: the resumed generation gives
// the one-shot generation's configuration and leaves the random generator in the same state.
TEST(Resumable, ResumedGenerationEqualsOneShotGeneration)
{
  const Inst in = big();
  const int n = static_cast<int>(in.s.size());
  DistTable d(in.g);
  d.set_goals(in.t);
  Pibt once(in.g, d), pieces(in.g, d);
  once.set_goals(in.t);
  pieces.set_goals(in.t);
  std::vector<int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  Rng shuffle(5), ra(11), rb(11);
  Config from = in.s, to(n);
  int paused_generations = 0;
  for (int step = 0; step < 30; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    shuffle.shuffle(order.data(), n);
    // Fix the first two agents in order: one stays, one takes its first neighbour.
    const int32_t a = order[0], b = order[1];
    Constraint root{};
    Constraint c1{&root, nullptr, a, from[a], 1};
    Constraint c2{&c1, nullptr, b, in.g.neighbors(from[b])[0], 2};
    const Constraint* c = step % 3 == 0 ? nullptr : &c2;
    const bool ok = once.generate(from.data(), order.data(), c, to.data(), ra);
    pieces.start(from.data(), order.data(), c);
    Pibt::Gen r;
    if (resume_in_pieces(pieces, rb, &r) > 2) ++paused_generations;
    ASSERT_EQ(r == Pibt::Gen::done, ok);
    EXPECT_FALSE(pieces.pending());
    EXPECT_EQ(ra.next(), rb.next()) << "the draws differ";
    if (!ok) continue;
    ASSERT_EQ(Config(pieces.result(), pieces.result() + n), to);
    from = to;
  }
  EXPECT_GT(paused_generations, 20);
}

// RT-LaCAM with a zero wall-clock budget (every expansion paused at every chance, the agents rerooting onto nodes meanwhile) builds full-horizon LaCAM's tree: the
// same expansions, and the same configuration for every node in creation order.
TEST(Resumable, PausedExpansionsBuildLacamsTree)
{
  int paused_moves = 0;  // over all runs
  for (const auto& in : instances()) {
    for (uint64_t seed = 0; seed < 4; ++seed) {
      SCOPED_TRACE(in.name + " seed " + std::to_string(seed));
      LacamOptions o = pausing();
      o.seed = seed;
      if (seed == 3) o.mc_rollouts = 3;  // Monte-Carlo rollouts pause and resume the same way
      DistTable d(in.g);
      Lacam full(in.g, d, o);
      full.reset(in.s, in.t);
      ASSERT_EQ(full.search(Budget::unlimited()), Status::Solved);

      RtLacam rt(in.g, in.s, in.t, o);
      Validator val(in.g, in.s, in.t);
      int paused_calls = 0;
      for (long long step = 0; !rt.at_goal(); ++step) {
        ASSERT_LT(step, 200000) << "no progress";
        rt.search(Budget::time_ms(0));
        paused_calls += rt.lacam().expansion_paused();
        const bool moves = rt.lacam().expansion_paused() && rt.next() != rt.current();
        rt.commit();  // a reroot while the expansion is paused
        paused_moves += moves;
        ASSERT_TRUE(val.step(rt.current())) << val.error();
      }
      std::string why;
      ASSERT_TRUE(rt.lacam().check_tree(&why)) << why;
      EXPECT_EQ(rt.expansions(), full.expansions());
      ASSERT_EQ(rt.explored(), full.explored());
      const int n = static_cast<int>(in.s.size());
      for (size_t id = 0; id < full.explored(); ++id)
        ASSERT_TRUE(std::equal(full.node(id)->C, full.node(id)->C + n, rt.lacam().node(id)->C)) << "node " << id;
      if (n >= 40) {
        EXPECT_GT(paused_calls, 0);
      }
    }
  }
  EXPECT_GT(paused_moves, 0) << "no reroot happened under a paused expansion";
}

// reset() drops a paused expansion: the new search makes only legal successors (no stale
// reservation of the dropped one) and solves its instance. A tree whose every expansion was
// dropped unended makes the next tree's first expansion end in its call.
TEST(Resumable, ResetDropsAPausedExpansion)
{
  const Inst in = big();
  DistTable d(in.g);
  Lacam lacam(in.g, d, pausing());
  lacam.reset(in.s, in.t);
  lacam.search(Budget::time_ms(0));
  ASSERT_TRUE(lacam.expansion_paused());
  lacam.reset(in.t, in.s);  // another search: start and goals swapped
  EXPECT_FALSE(lacam.expansion_paused());
  lacam.search(Budget::time_ms(0));
  EXPECT_FALSE(lacam.expansion_paused()) << "the first expansion after a dropped unended one must end";
  EXPECT_EQ(lacam.explored(), 2u);
  lacam.search(Budget::time_ms(0));
  EXPECT_TRUE(lacam.expansion_paused());
  lacam.reset(in.t, in.s);  // this tree had an ended expansion: the next may pause at once
  lacam.search(Budget::time_ms(0));
  EXPECT_TRUE(lacam.expansion_paused());
  ASSERT_EQ(lacam.search(Budget::unlimited()), Status::Solved);
  std::string why;
  EXPECT_TRUE(lacam.check_tree(&why)) << why;
  EXPECT_EQ(lacam.path(lacam.goal_node()).back(), in.s);
  // Every node after the reset is a legal successor of its parent (no stale reservation).
  for (size_t id = 1; id < lacam.explored(); ++id) {
    const HNode* h = lacam.node(id);
    const int n = lacam.num_agents();
    Config a(h->parent->C, h->parent->C + n), b(h->C, h->C + n);
    ASSERT_EQ(Validator::check_transition(in.g, a, b), "") << "node " << id;
  }
}

// Naive RT-LaCAM resets every iteration: its expansions never pause (the agents move in
// every iteration however small the budget).
TEST(Resumable, NaiveRtLacamNeverPauses)
{
  const Inst in = big();
  NaiveRtLacam naive(in.g, in.s, in.t);
  for (int step = 0; step < 5; ++step) {
    naive.search(Budget::time_ms(0));
    EXPECT_NE(naive.next(), naive.current()) << "step " << step;
    naive.commit();
  }
}

// set_immobile() cancels a paused generation; it restarts from the same draws under the new
// mask, giving the one-shot generation's successor with that mask.
TEST(Resumable, SetImmobileRestartsAPausedGeneration)
{
  const Inst in = big();
  const int n = static_cast<int>(in.s.size());
  DistTable d(in.g);
  d.set_goals(in.t);
  Pibt paused(in.g, d), once(in.g, d);
  paused.set_goals(in.t);
  once.set_goals(in.t);
  std::vector<int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::vector<uint8_t> mask(n, 0);
  for (int i = 0; i < n; i += 5) mask[i] = 1;
  Rng r0(7);
  paused.start(in.s.data(), order.data(), nullptr);
  Rng rp = r0;
  for (int k = 0; k < 6; ++k) ASSERT_EQ(paused.resume(rp, kPast), Pibt::Gen::paused);
  paused.set_immobile(mask);
  EXPECT_FALSE(paused.pending());
  rp = r0;
  paused.start(in.s.data(), order.data(), nullptr);
  ASSERT_EQ(paused.resume(rp), Pibt::Gen::done);
  once.set_immobile(mask);
  Config to(n);
  Rng ro = r0;
  ASSERT_TRUE(once.generate(in.s.data(), order.data(), nullptr, to.data(), ro));
  EXPECT_EQ(Config(paused.result(), paused.result() + n), to);
  for (int i = 0; i < n; i += 5) EXPECT_EQ(to[i], in.s[i]) << "immobile agent " << i << " moved";

  // Through Lacam: the paused expansion restarts itself; its successor keeps the immobile
  // agents (those no constraint fixes) in place and is a legal move.
  Lacam lacam(in.g, d, pausing());
  lacam.reset(in.s, in.t);
  lacam.search(Budget::expansion_count(3));
  lacam.search(Budget::time_ms(0));
  ASSERT_TRUE(lacam.expansion_paused());
  const HNode* H = lacam.top();
  const size_t before = lacam.explored();
  lacam.set_immobile(mask);
  while (lacam.expansion_paused()) lacam.search(Budget::time_ms(0));
  ASSERT_EQ(lacam.explored(), before + 1) << "expected a new node";
  const HNode* h = lacam.node(before);
  ASSERT_EQ(h->parent, H);
  Config a(H->C, H->C + n), b(h->C, h->C + n);
  EXPECT_EQ(Validator::check_transition(in.g, a, b), "");
  // The constraint of H's 2nd expansion fixes H's first agent in order at most.
  for (int i = 0; i < n; i += 5) {
    if (i != H->order[0]) {
      EXPECT_EQ(b[i], a[i]) << "immobile agent " << i << " moved";
    }
  }

  // However far the cancelled generation had gone (how many of its draws were made), the
  // restarted one makes the same successor.
  Lacam later(in.g, d, pausing());
  later.reset(in.s, in.t);
  later.search(Budget::expansion_count(3));
  for (int k = 0; k < 15; ++k) later.search(Budget::time_ms(0));
  ASSERT_TRUE(later.expansion_paused());
  later.set_immobile(mask);
  while (later.expansion_paused()) later.search(Budget::time_ms(0));
  ASSERT_EQ(later.explored(), before + 1);
  EXPECT_TRUE(std::equal(h->C, h->C + n, later.node(before)->C));
}

// The work of one timed call is bounded: with a zero budget, a call plans at most
// Pibt::kCheckEvery top-level agents. With resumability off each call plans all N.
TEST(Resumable, IterationWorkIsBounded)
{
  const Inst in = big();
  const int n = static_cast<int>(in.s.size());
  for (bool resumable : {true, false}) {
    SCOPED_TRACE(resumable ? "resumable" : "one-shot");
    LacamOptions o = pausing();
    o.resumable = resumable;
    RtLacam rt(in.g, in.s, in.t, o);
    uint64_t most = 0, calls = 0;
    for (int step = 0; step < 400 && !rt.at_goal(); ++step) {
      const uint64_t a0 = rt.lacam().agents_planned();
      rt.search(Budget::time_ms(0));
      most = std::max(most, rt.lacam().agents_planned() - a0), ++calls;
      rt.next();
      rt.commit();
    }
    ASSERT_GT(calls, 40u);
    if (resumable) EXPECT_LE(most, static_cast<uint64_t>(Pibt::kCheckEvery));
    else EXPECT_EQ(most, static_cast<uint64_t>(n));
  }
}

// Below LacamOptions::pause_min_ms an expansion is not paused: every call ends one (the
// paper's loop), so the agents never wait for a half-made successor. With a zero budget the
// deadline has always passed: with the floor (the default, 0.05 ms) each call still ends
// exactly one expansion and the agents follow it; without (0), calls end paused and the
// agents wait in most of them.
TEST(Resumable, BelowThePauseFloorEveryCallEndsAnExpansion)
{
  const Inst in = big();
  for (double floor_ms : {LacamOptions{}.pause_min_ms, 0.0}) {
    SCOPED_TRACE("pause_min_ms " + std::to_string(floor_ms));
    LacamOptions o;
    o.pause_min_ms = floor_ms;
    RtLacam rt(in.g, in.s, in.t, o);
    int paused = 0, waits = 0, calls = 0;
    for (int step = 0; step < 60 && !rt.at_goal(); ++step, ++calls) {
      const uint64_t e0 = rt.expansions();
      rt.search(Budget::time_ms(0));
      paused += rt.lacam().expansion_paused();
      if (floor_ms > 0) {
        ASSERT_FALSE(rt.lacam().expansion_paused()) << "step " << step;
        ASSERT_EQ(rt.expansions(), e0 + 1) << "step " << step;
      }
      waits += rt.next() == rt.current();
      rt.commit();
    }
    ASSERT_EQ(calls, 60);
    if (floor_ms > 0) {
      EXPECT_EQ(waits, 0);  // the DFS top is always one move ahead
    } else {
      EXPECT_GT(paused, 30);
      EXPECT_GT(waits, 30);
    }
  }
}
