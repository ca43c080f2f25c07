// The rotation solvers under the physical executors (run.executor: adg | adg-follow) on the
// real SUMO: the plan's cells go through the same ADG as a cell plan, the Driver turns each
// AGV on its cell toward its next move (fleet.turn_s per quarter turn, read back from SUMO)
// and drives it with the vType's kinematics, delays included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <regex>

#include "closed_loop_util.hpp"
#include "controller/bound.hpp"
#include "controller/commander.hpp"
#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "controller_test_util.hpp"
#include "planner/validator.hpp"
#include "temp_path.hpp"

using namespace controller;

namespace {

// The small warehouse with the shipped AGV physics (accel 0.5, decel 1.0, 1 m/s), 6 AGVs
// (the instance test_rotation.cpp's lockstep runs finish), deterministic budgets, fcd to
// 1e-6 for the kinematics and angles.
Config small_adg(const std::string& solver, const std::string& executor, const std::string& dir)
{
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse.yaml");
  c.output.dir = test::temp_dir(dir);
  c.run.progress_s = 0;
  c.run.max_ticks = 300;
  c.run.executor = executor;
  c.run.window = 4;
  c.run.replan_on_stuck = false;
  c.sumo.outputs = {true, false, false, true};
  c.sumo.extra_args = {"--precision", "6"};
  c.fleet.count = 6;
  c.fleet.seed = 1;
  c.fleet.vtype = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse_lifelong_agv.yaml").fleet.vtype;
  c.tasks.seed = 6;
  c.planner.solver = solver;
  c.planner.budget_ms = 0;
  c.planner.expansions = 20;
  return c;
}

// Per AGV, from fcd.xml: its angle while it stands (x, y unchanged to 1.1 mm, the 1 mm a
// front held at a lane's end may stand back). Every change of a standing AGV's angle must be
// one step of a quarter turn (90 / n degrees); `turns` counts the runs of n such steps
// (a delay may hold a turn where it got to for a while), `bad` any other change (an
// instant flip, a turn at the wrong rate, a run cut short by a move), `unfinished` the turns
// still running when the fcd ends (a lifelong run's tick limit came mid-turn: the AGV stays
// at rest at the angle it reached).
struct FcdTurns {
  long long turns = 0, bad = 0, unfinished = 0;
};
// n_of(id): the steps of a quarter turn of that vehicle (a slowed AGV's are more).
FcdTurns fcd_turns(const std::string& fcd, const std::function<int(const std::string&)>& n_of)
{
  const std::string s = ctest_util::slurp(fcd);
  const std::regex veh_re(R"re(<vehicle id="([^"]+)" x="([-0-9.e]+)" y="([-0-9.e]+)" angle="([-0-9.e]+)")re");
  struct Last {
    double x = NAN, y = NAN, angle = NAN;
    int run = 0;
  };
  std::map<std::string, Last> last;
  FcdTurns out;
  auto close = [&](Last& l, const std::string& id) {
    const int n = n_of(id);
    if (l.run == 0) return;
    if (l.run % n != 0) {
      ++out.bad;
      ADD_FAILURE() << id << ": a turn of " << l.run << " steps";
    }
    out.turns += l.run / n;
    l.run = 0;
  };
  for (auto it = std::sregex_iterator(s.begin(), s.end(), veh_re); it != std::sregex_iterator(); ++it) {
    const std::string id = (*it)[1];
    const int n = n_of(id);
    const double per_step = 90.0 / n;
    const double x = std::stod((*it)[2]), y = std::stod((*it)[3]), a = std::stod((*it)[4]);
    Last& l = last[id];
    const bool standing = std::hypot(x - l.x, y - l.y) <= 1.1e-3;
    if (standing) {
      const double d = std::remainder(a - l.angle, 360.0);
      if (std::fabs(d) < 1e-4) {
        if (l.run % n == 0) close(l, id);  // else a turn held by a delay: it goes on later
      } else if (std::fabs(std::fabs(d) - per_step) < 1e-4) {
        ++l.run;
      } else if (std::hypot(x - l.x, y - l.y) > 1e-6) {
        // Moving after all: creeping (under 1.1 mm in a step: braking to a stop) along a
        // curved junction lane, whose angle changes with the position. Seen once since
        // session 37 (epibt's leavers first): agv0 moved 0.994 mm and turned 0.11 degrees,
        // at 79.03 degrees (not on a lane's axis).
        close(l, id);
      } else {
        ++out.bad;
        ADD_FAILURE() << id << " turned " << d << " degrees in one step while standing";
      }
    } else {
      close(l, id);
    }
    l.x = x, l.y = y, l.angle = a;
  }
  for (auto& [id, l] : last) {
    out.unfinished += l.run % n_of(id) != 0;
    out.turns += l.run / n_of(id);
  }
  return out;
}

// What every run here must show: no error, collision, jump or re-sync; Safety after every
// SUMO step; no AGV braking harder than its vType (SUMO's own speeds); turns that SUMO
// shows as turn_s per quarter turn, as many as the Driver commanded, and that it waited for.
void expect_physical_turns(const Config& c, const Metrics& m)
{
  ctest_util::expect_checked_every_step(c, m);
  EXPECT_GT(m.commands.quarter_turns, 0) << "no turn executed: the run did not use headings";
  const int n = static_cast<int>(std::lround(c.fleet.turn_s / c.sumo.step_length));
  // Without delays a quarter turn is n Driver steps exactly (a held turn takes longer).
  if (c.delays.spec.kind == "none" && c.delays.spec.slow.empty()) {
    EXPECT_EQ(m.turn_steps, n * m.commands.quarter_turns);
  } else {
    // (A turn still running when a lifelong run ends has had fewer steps.)
    EXPECT_GE(m.turn_steps + (n - 1) * c.fleet.count, n * m.commands.quarter_turns);
  }
  // A slowed AGV (delays.slow, factor f) turns in ceil(n / f) steps.
  auto n_of = [&](const std::string& id) {
    double f = 1;
    for (const executor::Slowdown& s : c.delays.spec.slow)
      if (Commander::vehicle_id(s.agent) == id) f = s.factor;
    return static_cast<int>(std::ceil(n / f - 1e-9));
  };
  const FcdTurns t = fcd_turns(c.output.dir + "/fcd.xml", n_of);
  EXPECT_EQ(t.bad, 0);
  EXPECT_EQ(t.turns + t.unfinished, m.commands.quarter_turns);
  if (!c.tasks.lifelong()) {
    EXPECT_EQ(t.unfinished, 0);  // a one-shot run ends with every AGV home
  }
  const ctest_util::Kinematics k = ctest_util::fcd_kinematics(c.output.dir + "/fcd.xml", c.sumo.step_length);
  EXPECT_LE(k.max_decel, c.fleet.vtype.decel + 1e-4);
  EXPECT_LE(k.max_accel, c.fleet.vtype.accel + 1e-4);
  EXPECT_LE(k.max_speed, c.fleet.vtype.max_speed + 1e-6);
  EXPECT_GT(k.max_speed, 0);
}

void expect_one_shot(const std::string& solver, const std::string& executor)
{
  const Config c = small_adg(solver, executor, "ctl_rot_adg_" + solver + "_" + executor);
  Controller ctl(c);
  const Metrics m = ctl.run();
  EXPECT_TRUE(m.solved) << m.error;
  expect_physical_turns(c, m);
  // Every commit went through the validator and check_rotation_step; the executed plan
  // validates again here.
  const auto& plan = ctl.plan();
  ASSERT_FALSE(plan.empty());
  EXPECT_EQ(planner::validate_plan(ctl.map().graph, plan.front(), plan.back(), plan, true), "");
  // The physical bound counts the turns (rest + turn_s each): above the same paths driven
  // without them, and never above what the run took.
  const Kinematics kin{c.fleet.vtype.accel, c.fleet.vtype.decel, c.fleet.vtype.max_speed, c.sumo.step_length};
  const std::vector<double> plain = alone_s(ctl.map(), plan, kin);
  EXPECT_GT(m.plan_bound_ticks, *std::max_element(plain.begin(), plain.end()) / c.run.tick_s + c.fleet.turn_s / c.run.tick_s - 1e-9);
  EXPECT_LE(m.plan_bound_ticks, m.makespan);
  // The instance's (shortest ways, fewest turns) is below the plan's.
  EXPECT_GT(m.bound_ticks, 0);
  EXPECT_LE(m.bound_ticks, m.plan_bound_ticks + 1e-9);
}

void expect_lifelong(const std::string& solver, const std::string& executor)
{
  Config c = ctest_util::lifelong_agv_config("ctl_rot_life_" + solver + "_" + executor, 300);
  c.run.executor = executor;
  c.run.replan_on_stuck = false;
  c.planner.solver = solver;
  c.planner.budget_ms = 0;
  c.planner.expansions = 20;
  c.sumo.outputs = {true, false, false, true};
  c.sumo.extra_args = {"--precision", "6"};
  Controller ctl(c);
  const Metrics m = ctl.run();
  expect_physical_turns(c, m);  // with the config's Bernoulli stops (p = 0.01, 1-5 s)
  EXPECT_GT(m.delay_stops, 0) << "no delay happened: the run did not test turns under delays";
  EXPECT_GT(m.errands_finished, 5);
  EXPECT_LE(m.plan_bound_ticks, m.ticks);
}

}  // namespace

TEST(ControllerRotationAdg, PibtRotUnderAdgTurnsOnTheCellAndReachesAllGoals) { expect_one_shot("pibt-rot", "adg"); }
TEST(ControllerRotationAdg, EpibtUnderAdgFollowTurnsOnTheCellAndReachesAllGoals) { expect_one_shot("epibt", "adg-follow"); }
TEST(ControllerRotationAdg, WpplUnderAdgFollowTurnsOnTheCellAndReachesAllGoals) { expect_one_shot("wppl", "adg-follow"); }
TEST(ControllerRotationAdg, EpibtLifelongUnderAdgFollowWithDelays) { expect_lifelong("epibt", "adg-follow"); }
TEST(ControllerRotationAdg, PibtRotLifelongUnderAdgWithDelays) { expect_lifelong("pibt-rot", "adg"); }

// A 2 s turn (16 steps of 5.625 degrees) in a physical run: each quarter turn stands 16 SUMO
// steps on its cell, and the move waits for it.
TEST(ControllerRotationAdg, ATurnTakesTurnSecondsUnderAdg)
{
  Config c = small_adg("pibt-rot", "adg-follow", "ctl_rot_adg_turn2");
  c.fleet.turn_s = 2.0;
  Controller ctl(c);
  const Metrics m = ctl.run();
  EXPECT_TRUE(m.solved) << m.error;
  expect_physical_turns(c, m);
}

// A slowed AGV turns slower too (delays.slow, issue 20): with every AGV at half speed each
// quarter turn stands 2n SUMO steps on its cell (n = turn_s / step_length), in steps of
// 90 / 2n degrees, and the Driver waits for all of them.
TEST(ControllerRotationAdg, ASlowedAgvTurnsSlower)
{
  Config c = small_adg("pibt-rot", "adg-follow", "ctl_rot_adg_slow");
  for (int i = 0; i < c.fleet.count; ++i) c.delays.spec.slow.push_back({i, 0.5});
  Controller ctl(c);
  const Metrics m = ctl.run();
  EXPECT_TRUE(m.solved) << m.error;
  ctest_util::expect_checked_every_step(c, m);
  ASSERT_GT(m.commands.quarter_turns, 0);
  const int n = static_cast<int>(std::lround(c.fleet.turn_s / c.sumo.step_length));
  EXPECT_EQ(m.turn_steps, 2 * n * m.commands.quarter_turns);
  const FcdTurns t = fcd_turns(c.output.dir + "/fcd.xml", [&](const std::string&) { return 2 * n; });
  EXPECT_EQ(t.bad, 0);
  EXPECT_EQ(t.turns + t.unfinished, m.commands.quarter_turns);
  if (!c.tasks.lifelong()) {
    EXPECT_EQ(t.unfinished, 0);  // a one-shot run ends with every AGV home
  }
}

// A cell solver's reversal in an aisle is an instant 180-degree flip in SUMO (counted as
// instant_flips); given fleet.turn_s under adg-follow its AGVs turn on their cells like the
// rotation solvers' (two quarter turns of turn_s each), with no flip left.
TEST(ControllerRotationAdg, CellSolverReversalsAreTurnsInPlaceWithTurnS)
{
  auto run = [](bool turn, const std::string& name) {
    Config c = ctest_util::lifelong_agv_config(name, 200);
    c.planner.budget_ms = 0;
    c.planner.expansions = 20;
    c.fleet.turn_in_place = turn;
    c.sumo.outputs = {true, false, false, true};
    c.sumo.extra_args = {"--precision", "6"};
    Controller ctl(c);
    const Metrics m = ctl.run();
    ctest_util::expect_checked_every_step(c, m);
    EXPECT_GT(m.errands_finished, 5);
    return std::make_pair(c, m);
  };
  const auto [c0, flips] = run(false, "ctl_cell_flip");
  EXPECT_GT(flips.commands.flips, 0) << "no reversal in 200 ticks: the comparison shows nothing";
  EXPECT_EQ(flips.commands.quarter_turns, 0);
  const auto [c1, turns] = run(true, "ctl_cell_turn");
  EXPECT_EQ(turns.commands.flips, 0);
  expect_physical_turns(c1, turns);
}

TEST(ControllerRotationAdg, ConfigAcceptsTheExecutorsAndRefusesTheStuckReplan)
{
  const std::string sumo = "sumo:\n  net: ../sumo_scenarios/small.net.xml\n", net = sumo + "fleet: {count: 3}\n";
  const Config adg = parse_config(net + "planner: {solver: epibt}\nrun: {executor: adg}\n", "t.yaml", RTLACAM_CONFIGS);
  EXPECT_EQ(adg.run.executor, "adg");
  EXPECT_FALSE(adg.run.replan_on_stuck) << "the stuck replan rebuilds a cell planner";
  const Config follow = parse_config(net + "planner: {solver: wppl}\nrun: {executor: adg-follow}\n", "t.yaml", RTLACAM_CONFIGS);
  EXPECT_EQ(follow.run.executor, "adg-follow");
  EXPECT_EQ(ctest_util::config_error(net + "planner: {solver: pibt-rot}\nrun: {executor: adg, replan_on_stuck: true}\n"),
            "t.yaml: run.replan_on_stuck: only with a cell solver (rtlacam | naive | pibt | cspibt), not pibt-rot");
  // A cell solver with fleet.turn_s: turns in place under adg, refused in lockstep.
  EXPECT_TRUE(parse_config(sumo + "fleet: {count: 3, turn_s: 0.5}\nrun: {executor: adg-follow}\n", "t.yaml", RTLACAM_CONFIGS)
                  .fleet.turn_in_place);
  EXPECT_FALSE(parse_config(net + "run: {executor: adg-follow}\n", "t.yaml", RTLACAM_CONFIGS).fleet.turn_in_place);
  EXPECT_EQ(ctest_util::config_error(sumo + "fleet: {count: 3, turn_s: 0.3}\nrun: {executor: adg}\n"),
            "t.yaml: fleet.turn_s: must be a whole multiple of sumo.step_length (0.125)");
}
