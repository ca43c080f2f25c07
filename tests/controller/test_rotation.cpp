// The rotation solvers in SUMO (planner.solver: pibt-rot | epibt | wppl): AGVs with a
// heading, turns that take fleet.turn_s while the AGV stands on its cell, on the real SUMO.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "controller/bound.hpp"
#include "controller/commander.hpp"
#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "controller/sumo_error.hpp"
#include "controller/sumo_options.hpp"
#include "gridify/gridifier.hpp"
#include "controller_test_util.hpp"
#include "planner/rotation/epibt.hpp"
#include "planner/validator.hpp"
#include "temp_path.hpp"

using namespace controller;

namespace {

// The small warehouse with 6 AGVs (fleet seed 1, task seed 6: an instance all three rotation
// solvers finish; they are PIBT-based and incomplete -- 16 AGVs there livelock in the
// one-cell aisles, which is why rtlacam stays the default) and deterministic budgets.
Config small_rotation(const std::string& solver, const std::string& dir)
{
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse.yaml");
  c.output.dir = test::temp_dir(dir);
  c.run.progress_s = 0;
  c.run.max_ticks = 200;
  c.sumo.outputs = {false, false, false, true};
  c.fleet.count = 6;
  c.fleet.seed = 1;
  c.tasks.seed = 6;
  c.planner.solver = solver;
  c.planner.budget_ms = 0;
  c.planner.expansions = 20;
  return c;
}

// One-shot: all goals, nothing SUMO or the checks object to, turns really executed.
void expect_all_goals(const std::string& solver)
{
  const Config c = small_rotation(solver, "ctl_rot_" + solver);
  Controller ctl(c);
  const Metrics m = ctl.run();
  EXPECT_EQ(m.error, "");
  EXPECT_TRUE(m.solved);
  EXPECT_EQ(m.violations, 0);
  EXPECT_EQ(m.commands.jumps, 0);
  EXPECT_EQ(m.commands.resyncs, 0);
  EXPECT_GT(m.commands.quarter_turns, 0) << "no turn executed: the run did not use headings";
  // Every tick's committed step went through the validator (and check_rotation_step), and
  // Safety checked every SUMO step; the whole executed plan validates again here.
  EXPECT_EQ(m.commits, m.makespan);
  EXPECT_EQ(m.safety_checks, m.ticks * c.steps_per_tick());
  const auto& plan = ctl.plan();
  ASSERT_FALSE(plan.empty());
  EXPECT_EQ(planner::validate_plan(ctl.map().graph, plan.front(), plan.back(), plan, true), "");
  ctest_util::expect_no_sumo_collision(c.output.dir);
  // The physical bound counts each AGV's moves and the quarter turns they need: at least the
  // longest path in moves, never more than the run took.
  const std::vector<double> moves = alone_moves(plan);
  EXPECT_GE(m.plan_bound_ticks, *std::max_element(moves.begin(), moves.end()));
  EXPECT_LE(m.plan_bound_ticks, m.makespan);
  // The instance's (shortest ways, fewest turns) is below the plan's.
  EXPECT_GT(m.bound_ticks, 0);
  EXPECT_LE(m.bound_ticks, m.plan_bound_ticks + 1e-9);
}

}  // namespace

// The bound of a rotation plan: a move in a new direction first turns toward it, a quarter
// turn being one plan step (lockstep), a reversal two.
TEST(ControllerRotation, TheBoundCountsTheTurnsEachMoveNeeds)
{
  // 3 x 2 open grid: 0 1 2 / 3 4 5; headings 0 E, 1 S, 2 W, 3 N (planner/heading.hpp).
  const planner::Graph g = planner::Graph::from_grid(3, 2, std::vector<bool>(6, true));
  const std::vector<planner::Config> plan = {{0, 5}, {1, 5}, {2, 5}, {2, 5}, {5, 4}, {5, 3}};
  AloneBound plain(nullptr, {});
  AloneBound turning(nullptr, {});
  turning.count_turns(g, {0, 0});  // both face east
  for (const planner::Config& c : plan) plain.add(c), turning.add(c);
  // Agent 0: E, E, then S: 3 moves + 1 quarter turn. Agent 1: W, W from east: 2 + 2.
  EXPECT_EQ(plain.result(), (std::vector<double>{3, 2}));
  EXPECT_EQ(turning.result(), (std::vector<double>{4, 4}));
}

TEST(ControllerRotation, PibtRotReachesAllGoalsOnTheSmallWarehouse) { expect_all_goals("pibt-rot"); }
TEST(ControllerRotation, EpibtReachesAllGoalsOnTheSmallWarehouse) { expect_all_goals("epibt"); }
TEST(ControllerRotation, WpplReachesAllGoalsOnTheSmallWarehouse) { expect_all_goals("wppl"); }

// SUMO's angle of every standing AGV, step by step: a quarter turn is turn_s / step_length
// steps of 90 / N degrees each (here 2 s = 16 steps of 5.625 degrees, the tick stretched to
// two), never a jump; and there are as many such turns as the controller executed.
namespace {
void expect_turns_in_sumo(double factor, const std::string& name);
}

TEST(ControllerRotation, ATurnTakesTurnSecondsInSumo) { expect_turns_in_sumo(1.0, "ctl_rot_turn"); }

// A slowed AGV turns slower too (delays.slow): every AGV at half speed, a quarter turn is
// 2 x 16 steps of 2.8125 degrees (the tick stretched to four).
TEST(ControllerRotation, ASlowedAgvTurnsSlowerInLockstep) { expect_turns_in_sumo(0.5, "ctl_rot_turn_slow"); }

namespace {
void expect_turns_in_sumo(double factor, const std::string& name)
{
  Config c = small_rotation("pibt-rot", name);
  c.fleet.turn_s = 2.0;
  if (factor < 1)
    for (int i = 0; i < c.fleet.count; ++i) c.delays.spec.slow.push_back({i, factor});
  const int n = static_cast<int>(std::lround(c.fleet.turn_s / c.sumo.step_length / factor));
  const double per_step = 90.0 / n;
  Controller ctl(c);
  std::map<int, double> last_angle;
  std::map<int, VehiclePose> last_pose;
  std::map<int, int> run;  // consecutive steps of one turn direction, per agent
  long long turns_seen = 0, bad_steps = 0;
  auto close_run = [&](int i) {
    if (run[i] == 0) return;
    EXPECT_EQ(run[i] % n, 0) << "agent " << i << ": a turn of " << run[i] << " steps";
    turns_seen += run[i] / n;
    run[i] = 0;
  };
  // After every SUMO step: on_step (before the next step) sees it, except where a tick
  // starts -- the tick's commands (a moveTo) come before on_step there, so on_tick reads.
  bool tick_start = false;
  auto sample = [&](SumoBackend& sumo, const std::vector<VehiclePose>& poses) {
    for (int i = 0; i < static_cast<int>(poses.size()); ++i) {
      const double a = sumo.angle(Commander::vehicle_id(i));
      // Standing: on its cell (a front at a lane's end held at an angle: 1 mm back, SUMO's).
      const bool standing = last_pose.count(i) && last_pose[i].lane == poses[i].lane &&
                            std::fabs(last_pose[i].pos - poses[i].pos) <= 1.1e-3;
      if (standing) {
        const double d = std::remainder(a - last_angle[i], 360.0);
        if (std::fabs(d) < 1e-6) {
          close_run(i);
        } else if (std::fabs(std::fabs(d) - per_step) < 1e-6) {
          ++run[i];
        } else {
          ++bad_steps;  // an instant flip, or a turn at the wrong rate
          ADD_FAILURE() << "agent " << i << " turned " << d << " degrees in one step";
        }
      } else {
        close_run(i);
      }
      last_angle[i] = a;
      last_pose[i] = poses[i];
    }
  };
  ctl.on_tick = [&](long long, SumoBackend& sumo) {
    std::vector<VehiclePose> poses;
    for (int i = 0; i < c.fleet.count; ++i) poses.push_back(sumo.pose(Commander::vehicle_id(i)));
    sample(sumo, poses);
    tick_start = true;
  };
  ctl.on_step = [&](SumoBackend& sumo, const std::vector<VehiclePose>& poses) {
    if (!poses.empty() && !tick_start) sample(sumo, poses);
    tick_start = false;
  };
  const Metrics m = ctl.run();
  for (auto& [i, r] : run) close_run(i);
  EXPECT_EQ(m.error, "");
  EXPECT_TRUE(m.solved);
  EXPECT_EQ(bad_steps, 0);
  EXPECT_GT(m.commands.quarter_turns, 0);
  // A turn still running when the run ends is not closed; none here (all at their goals).
  EXPECT_EQ(turns_seen, m.commands.quarter_turns);
  EXPECT_EQ(m.commands.jumps + m.commands.resyncs, 0);
}
}  // namespace

// An AGV held at an angle (set_angle, every SUMO step while it faces off its lane) is
// map-matched only against lanes within SumoBackend::kAngleMatchRadius: on its own lane it
// stands at the angle asked, exactly where it was; a point 3 m off every lane is an error,
// where SUMO's default radius (100 m) searched -- and on the 1000-AGV warehouse scored --
// every lane around (~3 ms a call). Fails with the radius left at SUMO's default.
TEST(ControllerRotation, SetAngleMatchesOnlyLanesNearItsPoint)
{
  Config c = small_rotation("pibt-rot", "ctl_rot_match_radius");
  const gridify::CellMap map = gridify::gridify(c.sumo.net);
  // An aisle cell of the lowest row: nothing lies south of it.
  planner::Vertex v = -1;
  for (planner::Vertex u = 0; u < static_cast<planner::Vertex>(map.cells.size()); ++u)
    if (map.cells[u].kind == gridify::CellKind::Aisle && (v < 0 || map.cells[u].y < map.cells[v].y)) v = u;
  ASSERT_GE(v, 0);
  std::unique_ptr<SumoBackend> sumo = make_libsumo_backend();
  Commander cmd(map, *sumo, c.run.tick_s);
  sumo->start(sumo_args(c, c.output.dir, write_vtype_file(c, c.output.dir, c.grid.cell_length), false));
  cmd.insert({v});
  sumo->step();
  const VehiclePose at = sumo->pose("agv0");
  const std::string edge = at.lane.substr(0, at.lane.rfind('_'));
  const double angle = std::fmod(sumo->angle("agv0") + 90.0, 360.0);
  sumo->set_angle("agv0", at.lane, edge, at.pos, at.pos - 1e-4, angle, 0, 0);
  sumo->step();
  const VehiclePose held = sumo->pose("agv0");
  EXPECT_EQ(held.lane, at.lane);
  EXPECT_NEAR(held.pos, at.pos, 1.1e-3);
  EXPECT_NEAR(sumo->angle("agv0"), angle, 1e-6);
  EXPECT_THROW(sumo->set_angle("agv0", at.lane, edge, at.pos, at.pos - 1e-4, angle, 0, -3.0), SumoError)
      << "a point 3 m south of the lowest aisle was map-matched: the search radius is wider than kAngleMatchRadius";
  sumo->close();
}

TEST(ControllerRotation, HeldAgvsKeepPoseAndAngleWithOneRouteCallPerHold)
{
  // Commander::orient: an AGV turning or held at its heading's angle gets a moveToXY every
  // SUMO step, which cuts its route to the current edge; the route that goes on past the lane
  // is set again only when the hold starts (not every step: a replaceRoute in SUMO). Its
  // pose and angle hold all the same -- also on a junction cell, whose front stands at its
  // lane's end (a route ending there would let it arrive).
  Config c = small_rotation("pibt-rot", "ctl_rot_hold_route");
  const gridify::CellMap map = gridify::gridify(c.sumo.net);
  planner::Vertex v = -1, w = -1;
  for (planner::Vertex u = 0; u < static_cast<planner::Vertex>(map.cells.size()) && v < 0; ++u)
    if (map.cells[u].kind == gridify::CellKind::Aisle) v = u;
  ASSERT_GE(v, 0);
  for (planner::Vertex u = 0; u < static_cast<planner::Vertex>(map.cells.size()) && w < 0; ++u)
    if (map.cells[u].kind == gridify::CellKind::Junction &&
        std::abs(map.cells[u].x - map.cells[v].x) + std::abs(map.cells[u].y - map.cells[v].y) > 4)
      w = u;
  ASSERT_GE(w, 0);
  std::unique_ptr<SumoBackend> sumo = make_libsumo_backend();
  Commander cmd(map, *sumo, c.run.tick_s);
  sumo->start(sumo_args(c, c.output.dir, write_vtype_file(c, c.output.dir, c.grid.cell_length), false));
  cmd.insert({v, w});
  sumo->step();
  const std::vector<VehiclePose> at = {sumo->pose("agv0"), sumo->pose("agv1")};
  cmd.use_headings(cmd.start_headings({v, w}), 4);
  const long long routes = cmd.stats().route;
  cmd.begin_turn(0, 'R');
  cmd.begin_turn(1, 'C');
  for (int s = 0; s < 12; ++s) {  // 4 steps of turn, then 8 held at the new angle
    cmd.orient();
    sumo->step();
    for (int i = 0; i < 2; ++i) {
      const VehiclePose p = sumo->pose(cmd.ids()[i]);
      EXPECT_EQ(p.lane, at[i].lane) << "AGV " << i << ", step " << s;
      EXPECT_NEAR(p.pos, at[i].pos, 1.1e-3) << "AGV " << i << ", step " << s;
      if (s >= 3) {
        EXPECT_NEAR(std::remainder(cmd.angle(i) - Commander::sumo_angle(cmd.heading(i)), 360.0), 0.0, 1e-6)
            << "AGV " << i << ", step " << s;
      }
    }
  }
  EXPECT_EQ(sumo->vehicles().size(), 2u) << "an AGV left the network (arrived at its route's end)";
  EXPECT_EQ(cmd.stats().angle, 24);
  EXPECT_EQ(cmd.stats().route - routes, 2) << "the route is set when a hold starts, not every step";
  sumo->close();
}

TEST(ControllerRotation, BadRotationOptionsAreOneLineErrors)
{
  const std::string sumo = "sumo:\n  net: ../sumo_scenarios/small.net.xml\n", net = sumo + "fleet: {count: 3}\n";
  auto err = [&](const std::string& rest) { return ctest_util::config_error(net + rest); };
  EXPECT_EQ(err("planner: {solver: pibt-rot, rotation: {window: 5}}\n"),
            "t.yaml: planner.rotation.window: only with solver wppl, not pibt-rot");
  EXPECT_EQ(err("planner: {solver: rtlacam, rotation: {back_last: false}}\n"),
            "t.yaml: planner.rotation: only with a rotation solver (pibt-rot | epibt | wppl), not rtlacam");
  EXPECT_EQ(err("planner: {solver: epibt, rotation: {depth: 7}}\n"), "t.yaml: planner.rotation.depth: must be in 3..5, got 7");
  EXPECT_EQ(err("planner: {solver: wppl, rotation: {windw: 5}}\n").rfind("t.yaml: planner.rotation.windw: unknown key", 0), 0u);
  const std::string turn = ctest_util::config_error(sumo + "fleet: {count: 3, turn_s: 2}\n");
  EXPECT_EQ(turn.rfind("t.yaml: fleet.turn_s: only with a rotation solver", 0), 0u) << turn;
  EXPECT_EQ(ctest_util::config_error(sumo + "fleet: {count: 3, turn_s: 0.3}\nplanner: {solver: epibt}\n"),
            "t.yaml: fleet.turn_s: must be a whole multiple of sumo.step_length (0.125)");
  EXPECT_EQ(err("planner: {solver: epibt}\nrun: {executor: adg, replan_on_stuck: true}\n"),
            "t.yaml: run.replan_on_stuck: only with a cell solver (rtlacam | naive | pibt | cspibt), not epibt");
  EXPECT_EQ(err("planner: {solver: lacam}\n").rfind("t.yaml: planner.solver: 'lacam' is not one of", 0), 0u);
  // Accepted: each solver with its own options, and a turn of 0.5 s.
  const Config ok = parse_config(net + "planner: {solver: wppl, rotation: {window: 8, guidance: arrows}}\n", "t.yaml",
                                 RTLACAM_CONFIGS);
  EXPECT_EQ(ok.planner.rotation.window, 8);
  // Arrow guidance is every rotation solver's default (wppl since session 37); none is kept.
  for (const char* s : {"pibt-rot", "epibt", "wppl"})
    EXPECT_EQ(parse_config(net + "planner: {solver: " + s + "}\n", "t.yaml", RTLACAM_CONFIGS).planner.rotation.guidance,
              "arrows")
        << s;
  EXPECT_EQ(parse_config(net + "planner: {solver: wppl, rotation: {guidance: none}}\n", "t.yaml", RTLACAM_CONFIGS)
                .planner.rotation.guidance,
            "none");
  EXPECT_TRUE(ok.planner.rotation_solver());
  // epibt's pocket exit rule (EpibtOptions::pocket_exit): on unless the YAML turns it off.
  EXPECT_TRUE(ok.planner.rotation.pocket_exit);
  EXPECT_FALSE(parse_config(net + "planner: {solver: epibt, rotation: {pocket_exit: false}}\n", "t.yaml", RTLACAM_CONFIGS)
                   .planner.rotation.pocket_exit);
  // Since session 37 every rotation solver has it (pibt-rot, wppl: pocket_exit.hpp); leavers
  // first is epibt's own switch.
  EXPECT_FALSE(parse_config(net + "planner: {solver: pibt-rot, rotation: {pocket_exit: false}}\n", "t.yaml", RTLACAM_CONFIGS)
                   .planner.rotation.pocket_exit);
  EXPECT_TRUE(ok.planner.rotation.leavers_first);
  EXPECT_EQ(err("planner: {solver: pibt-rot, rotation: {leavers_first: false}}\n"),
            "t.yaml: planner.rotation.leavers_first: only with solver epibt, not pibt-rot");
  // epibt's replans per robot per step (EpibtOptions::revisit): the planner's default unless set.
  EXPECT_EQ(parse_config(net + "planner: {solver: epibt}\n", "t.yaml", RTLACAM_CONFIGS).planner.rotation.revisit,
            planner::EpibtOptions{}.revisit);
  EXPECT_EQ(parse_config(net + "planner: {solver: epibt, rotation: {revisit: 25}}\n", "t.yaml", RTLACAM_CONFIGS)
                .planner.rotation.revisit,
            25);
  EXPECT_EQ(err("planner: {solver: epibt, rotation: {revisit: 0}}\n"), "t.yaml: planner.rotation.revisit: must be in 1..1000000, got 0");
  EXPECT_EQ(err("planner: {solver: wppl, rotation: {revisit: 50}}\n"),
            "t.yaml: planner.rotation.revisit: only with solver epibt, not wppl");

  // A net whose cells are not on a lattice: refused before SUMO starts, naming the net.
  Config diag = parse_config("sumo:\n  net: " + std::string(RTLACAM_CONTROLLER_DATA) +
                                 "/diagonal.net.xml\nfleet: {count: 2}\nplanner: {solver: pibt-rot}\n",
                             "t.yaml", RTLACAM_CONFIGS);
  diag.output.dir = test::temp_dir("ctl_rot_diag");
  try {
    Controller(diag).run();
    ADD_FAILURE() << "the diagonal net ran with pibt-rot";
  } catch (const ConfigError& e) {
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("t.yaml: planner.solver: pibt-rot needs a net whose cells lie on an axis-aligned lattice", 0), 0u) << w;
    EXPECT_NE(w.find("diagonal.net.xml"), std::string::npos) << w;
    EXPECT_EQ(w.find('\n'), std::string::npos) << w;
  }
}
