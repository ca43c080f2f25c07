// Traffic rules with the rotation solvers (pibt-rot, epibt, wppl) on the real SUMO: when the
// rules' graph changes the planner restarts on it from the AGVs' cells and headings
// (rules.hpp; lockstep Run::rules_restart, adg / adg-follow Run::replan). Every run is
// checked after every SUMO step by Safety and RuleCheck, the Commander refuses a forward
// move an AGV does not face (a heading lost at a restart ends the run with an error), and
// expect_clean() checks no jump, no re-sync and the executed plan. Each rule switched off
// (rules.enforce_*, the lane watch) fails the same checks, as in test_rules.cpp.
#include <gtest/gtest.h>

#include <libsumo/libsumo.h>

#include <algorithm>

#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "rules_test_util.hpp"

using namespace controller;
using namespace rules_test;

namespace {

const std::string kClosure = "rules:\n  closures:\n    - {edges: [c1r0_c1r1, c1r1_c1r0], begin: 0, end: 25}\n";
// One zone over the two middle picking aisles c1 and c2 (x = 4 and 8 m, y = 1..7 m): with
// guidance (arrows) or without, kOneBehind's AGVs go down one of them.
const std::string kZone = R"(  <poly id="z_mid" type="rtlacam.zone" shape="3.5,0.5 8.5,0.5 8.5,7.5 3.5,7.5"/>
)";

// Two AGVs one behind the other on the top cross aisle (c0r1 -> c1r1, facing east), both
// with goals in the bottom row that are shortest down aisle c1: the second would follow the
// first into it.
const char* const kOneBehind = R"(
fleet:
  starts:
    - {lane: c0r1_c1r1_0, pos: 3}
    - {lane: c0r1_c1r1_0, pos: 2}
tasks:
  mode: one_shot
  goals:
    - {lane: c1r0_c0r0_0, pos: 2}
    - {lane: c1r0_c2r0_0, pos: 2}
)";

// At most one AGV in the zone (aisles c1 and c2) in every executed configuration.
void expect_one_in_zone(const Controller& c)
{
  std::vector<planner::Vertex> zone = aisle_cells(c.map(), kAisleC1);
  const std::vector<planner::Vertex> c2 = aisle_cells(c.map(), "c2r0_c2r1");
  ASSERT_EQ(c2.size(), 7u);
  zone.insert(zone.end(), c2.begin(), c2.end());
  for (const planner::Config& q : c.plan())
    EXPECT_LE(std::count_if(q.begin(), q.end(), [&](planner::Vertex v) { return in(zone, v); }), 1);
}

}  // namespace

// Lockstep, aisle c1 closed over [0, 25 s): pibt-rot restarts on the rules' graph at each
// change; agv1 (inside, facing up the aisle) turns and leaves by the evacuation arcs, agv2
// goes round, agv0 (goal inside) waits for the reopening. Not enforced: RuleCheck stops it.
TEST(RulesRotation, PibtRotRoutesAroundAClosureInLockstep)
{
  Config cfg = rules_config("rot_closure", kAround, "", kClosure, "pibt-rot");
  Controller c(cfg);
  expect_closure_kept(cfg, c, c.run());

  Config off = rules_config("rot_closure_off", kAround, "", kClosure + "  enforce_closures: false\n", "pibt-rot");
  Controller co(off);
  const Metrics mo = co.run();
  EXPECT_NE(mo.error.find("entered closed cell"), std::string::npos) << mo.error;
  EXPECT_EQ(mo.violations, 1);
}

// The same closure from a rerouter in the additional file, with epibt and wppl.
TEST(RulesRotation, EpibtAndWpplRouteAroundARerouterClosureInLockstep)
{
  const std::string add = additional("rot_rerouter", kRerouter);
  for (const char* solver : {"epibt", "wppl"}) {
    SCOPED_TRACE(solver);
    Config cfg = rules_config(std::string("rot_rerouter_") + solver, kAround, add, "", solver);
    Controller c(cfg);
    expect_closure_kept(cfg, c, c.run());
  }
}

// adg-follow, the closure begins at 1 s while the AGVs drive: the replan cuts the plan at
// each AGV's progress and restarts the rotation solver where the moves in progress end, at
// the heading of each AGV's last running move (or the one the Driver turned it to).
TEST(RulesRotation, AdgFollowClosureReplansRotationSolversFromTheObservedState)
{
  const std::string rules = "rules:\n  closures:\n    - {edges: [c1r0_c1r1, c1r1_c1r0], begin: 1, end: 25}\n";
  for (const char* solver : {"pibt-rot", "wppl"}) {
    SCOPED_TRACE(solver);
    Config cfg = rules_config(std::string("rot_adg_closure_") + solver, kAround, "", rules, solver);
    cfg.run.executor = "adg-follow";
    Controller c(cfg);
    const Metrics m = c.run();
    expect_clean(cfg, c, m);
    EXPECT_EQ(m.rules.closure_changes, 2);  // closed at 1 s, reopened at 25 s
    EXPECT_GE(m.rules.replans, 2);
    EXPECT_GT(m.rules.waits, 0);  // agv0 waited for its goal
    ASSERT_EQ(m.goal_s.size(), 3u);
    EXPECT_GE(m.goal_s[0], 25.0);  // on its goal (inside the aisle) only after it reopened
    EXPECT_GT(m.commands.quarter_turns, 0);
  }
  Config off = rules_config("rot_adg_closure_off", kAround, "", rules + "  enforce_closures: false\n", "pibt-rot");
  off.run.executor = "adg-follow";
  Controller co(off);
  const Metrics mo = co.run();
  EXPECT_NE(mo.error.find("entered closed cell"), std::string::npos) << mo.error;
}

// Another TraCI client disallows the AGVs' class on both lanes of aisle c1 at tick 0 and
// allows it again at tick 25; the lane watch sees it and pibt-rot restarts around it. agv1,
// on a closed lane, waits there (SUMO refuses every route from it). Without the watch SUMO
// refuses a route the plan needs.
TEST(RulesRotation, PibtRotReplansWhenALanePermissionChangesOverTraci)
{
  auto close_c1 = close_c1_lanes(0, 25, {"passenger"});
  Config cfg = rules_config("rot_traci", kAround, "", "rules: {watch_lanes: true}\n", "pibt-rot");
  Controller c(cfg);
  c.on_tick = close_c1;
  const Metrics m = c.run();
  expect_clean(cfg, c, m);
  EXPECT_EQ(entries(c.plan(), aisle_cells(c.map(), kAisleC1), 0, 25), 0);
  EXPECT_GE(first_at(c.plan(), 0, c.map().locate("c1r0_c1r1_0", 4)), 25);
  EXPECT_EQ(m.rules.closure_changes, 2);

  Config off = rules_config("rot_traci_off", kAround, "", "rules: {watch_lanes: false}\n", "pibt-rot");
  Controller co(off);
  co.on_tick = close_c1;
  const Metrics mo = co.run();
  EXPECT_NE(mo.error.find("Route replacement failed"), std::string::npos) << mo.error;
}

// A one-at-a-time zone (kZone, a SUMO polygon) that two AGVs drive into one after the other
// (kOneBehind): in lockstep admit() holds the second and the solver restarts from the
// executed configuration and headings; under adg-follow the Driver's mutex holds it and
// the zone leaves the graph by a replan. At most one AGV in the zone at any tick; not
// enforced, RuleCheck stops the run.
TEST(RulesRotation, ZoneHoldsOneAgvAtATimeWithRotationSolvers)
{
  const std::string add = additional("rot_zone", kZone);
  struct Case {
    const char* solver;
    const char* executor;
  };
  for (const Case& k : {Case{"pibt-rot", "lockstep"}, Case{"epibt", "lockstep"}, Case{"wppl", "lockstep"},
                        Case{"pibt-rot", "adg-follow"}, Case{"epibt", "adg-follow"}}) {
    SCOPED_TRACE(std::string(k.solver) + " " + k.executor);
    Config cfg = rules_config(std::string("rot_zone_") + k.solver + "_" + k.executor, kOneBehind, add, "", k.solver);
    cfg.run.executor = k.executor;
    Controller c(cfg);
    const Metrics m = c.run();
    expect_clean(cfg, c, m);
    expect_one_in_zone(c);
    EXPECT_GT(m.rules.zone_holds, 0);  // someone was held at the entry

    Config off = rules_config(std::string("rot_zone_off_") + k.solver + "_" + k.executor, kOneBehind, add,
                              "rules: {enforce_zones: false}\n", k.solver);
    off.run.executor = k.executor;
    Controller co(off);
    const Metrics mo = co.run();
    EXPECT_NE(mo.error.find("zone 'z_mid'"), std::string::npos) << mo.error;
    EXPECT_NE(mo.error.find("holds two AGVs"), std::string::npos) << mo.error;
  }
}

// The shipped lifelong rules example (a rerouter closure, a zone, a YAML closure at 100 s)
// with pibt-rot (lockstep) and wppl (adg-follow), their default guidance, 110 ticks: clean,
// errands done.
TEST(RulesRotation, ShippedLifelongRulesExampleRunsCleanWithRotationSolvers)
{
  const std::string yaml = ctest_util::slurp(std::string(RTLACAM_CONFIGS) + "/small_rules_lifelong.yaml");
  ASSERT_NE(yaml.find("solver: rtlacam"), std::string::npos);
  for (const auto& [solver, executor] : {std::make_pair("pibt-rot", "lockstep"), std::make_pair("wppl", "adg-follow")}) {
      SCOPED_TRACE(std::string(solver) + " " + executor);
      std::string text = yaml;
      text.replace(text.find("solver: rtlacam"), 15, std::string("solver: ") + solver);
      Config cfg = parse_config(text, "small_rules_lifelong.yaml", RTLACAM_CONFIGS);
      cfg.run.executor = executor;
      cfg.run.max_ticks = 110;
      cfg.run.progress_s = 0;
      cfg.planner.budget_ms = 0;
      cfg.planner.expansions = 100;
      cfg.output.dir = test::temp_dir(std::string("rot_lifelong_") + solver + "_" + executor);
      Controller c(cfg);
      const Metrics m = c.run();
      EXPECT_EQ(m.error, "");
      EXPECT_EQ(m.violations, 0);
      EXPECT_EQ(m.commands.jumps + m.commands.resyncs, 0);
      EXPECT_GE(m.rules.closure_changes, 2);  // the rerouter's closure began and ended
      EXPECT_GT(m.errands_finished, 5);
      ctest_util::expect_no_sumo_collision(cfg.output.dir);
    }
}
