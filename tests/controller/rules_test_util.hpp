#pragma once
// The fixtures of the traffic-rule tests on the real SUMO (test_rules.cpp: cell solvers,
// test_rules_rotation.cpp: rotation solvers): the small warehouse with a few AGVs round
// picking aisle c1, rules configs, and the checks every rules run must pass.
//
// The small warehouse (sumo_scenarios/small.net.xml): junctions c0..c3 (x = 0, 4, 8, 12 m)
// in rows r0 (y = 0) and r1 (y = 8); picking aisles c_i r0 - c_i r1 (7 cells), cross aisles
// along the rows (3 cells), stubs pick1/pick2 below r0 and drop0/drop3 above r1.
#include <gtest/gtest.h>

#include <libsumo/libsumo.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "controller_test_util.hpp"
#include "planner/validator.hpp"
#include "temp_path.hpp"

namespace rules_test {

using namespace controller;

inline const std::string kAisleC1 = "c1r0_c1r1";  // picking aisle c1 (and c1r1_c1r0 back)

// Three AGVs around picking aisle c1: agv0's goal is in it, agv1 starts in it, agv2's
// shortest route runs down it (10 moves; around it 16).
inline const char* const kAround = R"(
fleet:
  starts:
    - {lane: c0r0_c1r0_0, pos: 1}
    - {lane: c1r0_c1r1_0, pos: 3}
    - {lane: c0r1_c1r1_0, pos: 3}
tasks:
  mode: one_shot
  goals:
    - {lane: c1r0_c1r1_0, pos: 4}
    - {lane: c2r0_c2r1_0, pos: 4}
    - {lane: c1r0_c2r0_0, pos: 1}
)";

// Two AGVs that both want down aisle c1 from the top row at the same time.
inline const char* const kBothDown = R"(
fleet:
  starts:
    - {lane: c0r1_c1r1_0, pos: 3}
    - {lane: c2r1_c1r1_0, pos: 3}
tasks:
  mode: one_shot
  goals:
    - {lane: c1r0_c0r0_0, pos: 2}
    - {lane: c1r0_c2r0_0, pos: 2}
)";

// solver: planner.solver (a rotation solver gets the same budget: 200 expansions, no clock).
inline Config rules_config(const std::string& name, const std::string& agents, const std::string& additional,
                           const std::string& rules, const std::string& solver = "rtlacam")
{
  const std::string dir = test::temp_dir("rules_" + name);
  std::string yaml = "sumo:\n  net: ../sumo_scenarios/small.net.xml\n";
  if (!additional.empty()) yaml += "  additional: " + additional + "\n";
  yaml += "  step_length: 0.125\n  outputs: {fcd: false, tripinfo: false, summary: false, collision: true}\n";
  yaml += agents;
  yaml += "planner: {solver: " + solver + ", budget_ms: 0, expansions: 200, seed: 0}\n";
  yaml += "run: {tick_s: 1.0, max_ticks: 200, backend: libsumo, progress_s: 0}\n";
  yaml += "output: {dir: " + dir + "}\n";
  yaml += rules;
  return parse_config(yaml, "rules_" + name + ".yaml", RTLACAM_CONFIGS);
}

// Another TraCI client's view of SUMO (Controller::on_tick): at tick `from` both lanes of
// aisle c1 disallow `classes`, at tick `to` they allow every class again.
inline std::function<void(long long, controller::SumoBackend&)> close_c1_lanes(long long from, long long to,
                                                                               std::vector<std::string> classes)
{
  return [from, to, classes](long long tick, controller::SumoBackend&) {
    for (const char* l : {"c1r0_c1r1_0", "c1r1_c1r0_0"}) {
      if (tick == from) libsumo::Lane::setDisallowed(l, classes);
      if (tick == to) libsumo::Lane::setDisallowed(l, {});
    }
  };
}

inline std::string additional(const std::string& name, const std::string& body)
{
  return test::temp_file(name + ".add.xml", "<additional>\n" + body + "</additional>\n");
}

inline const std::string kRerouter = R"(  <rerouter id="close_c1" edges="c1r0_c1r1 c1r1_c1r0">
    <interval begin="0" end="25">
      <closingReroute id="c1r0_c1r1"/>
      <closingReroute id="c1r1_c1r0"/>
    </interval>
  </rerouter>
)";

// The interior cells of the aisle of `edge`.
inline std::vector<planner::Vertex> aisle_cells(const gridify::CellMap& map, const std::string& edge)
{
  for (const gridify::Aisle& a : map.aisles)
    if (a.ab == edge || a.ba == edge) return {a.cells.begin() + 1, a.cells.end() - 1};
  return {};
}

inline bool in(const std::vector<planner::Vertex>& cells, planner::Vertex v)
{
  return std::find(cells.begin(), cells.end(), v) != cells.end();
}

// Moves of the executed plan into `cells` while they are closed (ticks [from, to)).
inline int entries(const std::vector<planner::Config>& plan, const std::vector<planner::Vertex>& cells, long from, long to)
{
  int n = 0;
  for (size_t t = 1; t < plan.size(); ++t)
    for (size_t i = 0; i < plan[t].size(); ++i)
      n += static_cast<long>(t) > from && static_cast<long>(t) <= to && in(cells, plan[t][i]) && !in(cells, plan[t - 1][i]);
  return n;
}

// The first tick agent i stands on `v` in the executed plan (-1: never).
inline long first_at(const std::vector<planner::Config>& plan, size_t i, planner::Vertex v)
{
  for (size_t t = 0; t < plan.size(); ++t)
    if (plan[t][i] == v) return static_cast<long>(t);
  return -1;
}

inline void expect_clean(const Config& cfg, const Controller& c, const Metrics& m)
{
  EXPECT_EQ(m.error, "");
  EXPECT_TRUE(m.solved);
  EXPECT_EQ(m.violations, 0);
  EXPECT_EQ(m.commands.jumps + m.commands.resyncs, 0);
  EXPECT_EQ(m.rules.checks, m.ticks * cfg.steps_per_tick());  // RuleCheck after every step
  const auto& plan = c.plan();
  EXPECT_EQ(planner::validate_plan(c.map().graph, plan.front(), plan.back(), plan, true), "");
  ctest_util::expect_no_sumo_collision(cfg.output.dir);
}

// The closure of aisle c1 over [0, 25 s): nobody enters it, agv1 leaves it, agv0 (goal
// inside) reaches its goal only after it reopens, agv2 goes round.
inline void expect_closure_kept(const Config& cfg, const Controller& c, const Metrics& m)
{
  expect_clean(cfg, c, m);
  const std::vector<planner::Vertex> closed = aisle_cells(c.map(), kAisleC1);
  ASSERT_EQ(closed.size(), 7u);
  EXPECT_EQ(entries(c.plan(), closed, 0, 25), 0);
  const planner::Vertex goal0 = c.map().locate("c1r0_c1r1_0", 4);
  EXPECT_GE(first_at(c.plan(), 0, goal0), 25);
  ASSERT_GT(c.plan().size(), 10u);
  EXPECT_FALSE(in(closed, c.plan()[10][1]));  // agv1 left the closed aisle
  EXPECT_EQ(m.rules.closure_changes, 1);      // reopened at 25 s
  EXPECT_EQ(m.rules.max_closed, 7);
  EXPECT_GT(m.rules.waits, 0);                // agv0 waited for its goal
}


}  // namespace rules_test
