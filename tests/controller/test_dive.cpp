// planner.dive in the controller: the YAML key (default on), and real SUMO runs of the
// default demo (config/small_warehouse.yaml) with dives on and off under a deterministic
// budget (expansions per SUMO step), several planner seeds. Without dives the agents execute
// most of LaCAM's first solution (3-4x the bound on its one-cell aisles) before refinement
// improves it; PIBT rollouts from the root give a far cheaper path early.
#include <gtest/gtest.h>

#include <cstdio>

#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "controller_test_util.hpp"
#include "planner/validator.hpp"
#include "temp_path.hpp"

using namespace controller;

namespace {

const std::string kNet = "sumo:\n  net: ../sumo_scenarios/small.net.xml\n";

// libsumo holds one simulation per process: the runs after the first go through TraCI.
Metrics run_demo(bool dive, uint64_t seed, const std::string& backend, bool free_first = false,
                 std::vector<planner::Config>* plan_out = nullptr, int startup_ticks = 1, uint64_t expansions = 100)
{
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse.yaml");
  c.output.dir = test::temp_dir("ctl_dive_" + std::to_string(dive) + "_" + std::to_string(seed) + (free_first ? "_ff" : "") +
                                "_s" + std::to_string(startup_ticks) + "_e" + std::to_string(expansions));
  c.run.progress_s = 0;
  c.planner.budget_ms = 0;  // deterministic: expansions per SUMO step
  c.planner.expansions = expansions;
  c.planner.seed = seed;
  c.planner.startup_ticks = startup_ticks;
  c.planner.dive = dive;
  c.planner.free_first = free_first;
  c.run.backend = backend;
  Controller ctl(c);
  Metrics m = ctl.run();
  const auto& plan = ctl.plan();
  EXPECT_FALSE(plan.empty());
  if (!plan.empty()) {
    EXPECT_EQ(planner::validate_plan(ctl.map().graph, plan.front(), plan.back(), plan, true), "");
  }
  if (plan_out) *plan_out = plan;
  ctest_util::expect_no_sumo_collision(c.output.dir);
  EXPECT_EQ(m.error, "");
  EXPECT_TRUE(m.solved);
  EXPECT_EQ(m.violations, 0);
  return m;
}

}  // namespace

TEST(ControllerDive, YamlKeyDefaultsOnAndParses)
{
  EXPECT_TRUE(parse_config(kNet + "fleet: {count: 3}\n", "t.yaml", RTLACAM_CONFIGS).planner.dive);
  EXPECT_FALSE(parse_config(kNet + "fleet: {count: 3}\nplanner: {dive: false}\n", "t.yaml", RTLACAM_CONFIGS).planner.dive);
  EXPECT_THROW(parse_config(kNet + "fleet: {count: 3}\nplanner: {dive: maybe}\n", "t.yaml", RTLACAM_CONFIGS),
               std::exception);
}

// planner.stop_cost / planner.lns_moves (issue 21, LNS's tie-break for physical executors):
// off by default, parsed, and a negative cost is a one-line error naming the key.
TEST(ControllerDive, StopCostKeysDefaultOffAndParse)
{
  const Config d = parse_config(kNet + "fleet: {count: 3}\n", "t.yaml", RTLACAM_CONFIGS);
  EXPECT_EQ(d.planner.stop_cost, 0);
  EXPECT_FALSE(d.planner.lns_moves);
  const Config c = parse_config(kNet + "fleet: {count: 3}\nplanner: {stop_cost: 2, lns_moves: true}\n", "t.yaml", RTLACAM_CONFIGS);
  EXPECT_EQ(c.planner.stop_cost, 2);
  EXPECT_TRUE(c.planner.lns_moves);
  try {
    parse_config(kNet + "fleet: {count: 3}\nplanner: {stop_cost: -1}\n", "t.yaml", RTLACAM_CONFIGS);
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("planner.stop_cost"), std::string::npos) << e.what();
  }
}

TEST(ControllerDive, DemoExecutesACheaperStandardSocWithDives)
{
  double on_sum = 0, off_sum = 0;
  for (uint64_t seed = 0; seed < 3; ++seed) {
    SCOPED_TRACE("planner.seed " + std::to_string(seed));
    const Metrics on = run_demo(true, seed, seed == 0 ? "libsumo" : "traci");
    const Metrics off = run_demo(false, seed, "traci");
    EXPECT_LT(on.soc, off.soc);
    on_sum += static_cast<double>(on.soc) / on.soc_lb;
    off_sum += static_cast<double>(off.soc) / off.soc_lb;
  }
  // Measured: 2.21 x the bound with dives against 3.55 without (mean of the three seeds).
  EXPECT_LT(on_sum, 0.8 * off_sum);
}

// planner.free_first (issue 22's PIBT tie-break, on in the CLI's RT-LaCAM*): on by default in
// SUMO too since session 44 (lifelong gains, controller/README.md), parsed, and it reaches the
// planner: the same deterministic demo run plans differently with it.
TEST(ControllerDive, FreeFirstKeyDefaultsOnAndReachesThePlanner)
{
  EXPECT_TRUE(parse_config(kNet + "fleet: {count: 3}\n", "t.yaml", RTLACAM_CONFIGS).planner.free_first);
  EXPECT_FALSE(parse_config(kNet + "fleet: {count: 3}\nplanner: {free_first: false}\n", "t.yaml", RTLACAM_CONFIGS).planner.free_first);
  EXPECT_THROW(parse_config(kNet + "fleet: {count: 3}\nplanner: {free_first: maybe}\n", "t.yaml", RTLACAM_CONFIGS),
               std::exception);
  std::vector<planner::Config> off, on, off_again;
  run_demo(true, 0, "traci", false, &off);
  run_demo(true, 0, "traci", true, &on);
  run_demo(true, 0, "traci", false, &off_again);
  EXPECT_TRUE(off == off_again) << "the demo run is not deterministic";  // so a difference below is the key's
  EXPECT_FALSE(off == on) << "planner.free_first did not reach the planner";
}

// planner.startup_ticks (default 1): the first command waits for a tick's planning, as every
// later one does, instead of the insertion step's one SUMO step. On the default demo the first
// moves decide the cost (a long search at the start finds 243-249, from the fourth move on it
// cannot get below 277-283): deterministic, 1000 expansions per SUMO step, planner seeds 0-5,
// free_first on, measured 256.8 with against 274.8 without.
TEST(ControllerDive, StartupPlanningGivesTheFirstMoveATicksBudget)
{
  const Config d = parse_config(kNet + "fleet: {count: 3}\n", "t.yaml", RTLACAM_CONFIGS);
  EXPECT_EQ(d.planner.startup_ticks, 1);
  try {
    parse_config(kNet + "fleet: {count: 3}\nplanner: {startup_ticks: -1}\n", "t.yaml", RTLACAM_CONFIGS);
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("planner.startup_ticks"), std::string::npos) << e.what();
  }
  double with = 0, without = 0;
  for (uint64_t seed = 0; seed < 6; ++seed) {
    SCOPED_TRACE("planner.seed " + std::to_string(seed));
    const Metrics on = run_demo(true, seed, "traci", true, nullptr, 1, 1000);
    const Metrics off = run_demo(true, seed, "traci", true, nullptr, 0, 1000);
    // Without it the search before the first command had one SUMO step's budget.
    EXPECT_LE(off.planner_startup_expansions, 1000u);
    EXPECT_GT(on.planner_startup_expansions, 0u);
    with += static_cast<double>(on.soc);
    without += static_cast<double>(off.soc);
  }
  std::printf("executed SOC, mean of 6: %.1f with startup planning, %.1f without\n", with / 6, without / 6);
  EXPECT_LT(with, 0.97 * without);
}

// planner.highways (planner/highways.hpp; on in the CLI's RT-LaCAM*, off in SUMO by default:
// docs/rt_lacam_star.md "Session 46"): parsed with its range, and a large-warehouse run with it
// finishes. On this instance (200 AGVs, fleet seed 2, lock-step, 50 expansions per SUMO step)
// PIBT's swap decided on the plain distances while its moves were ranked by the highway ones:
// one AGV stayed short of its goal for 6000 ticks. Deciding on the ranking distances, it
// finishes in 328 ticks (330 without highways).
TEST(ControllerHighways, KeyParsesAndALargeWarehouseRunWithItFinishes)
{
  EXPECT_EQ(parse_config(kNet + "fleet: {count: 3}\n", "t.yaml", RTLACAM_CONFIGS).planner.highways, 0);
  EXPECT_EQ(parse_config(kNet + "fleet: {count: 3}\nplanner: {highways: 2}\n", "t.yaml", RTLACAM_CONFIGS).planner.highways, 2);
  try {
    parse_config(kNet + "fleet: {count: 3}\nplanner: {highways: -1}\n", "t.yaml", RTLACAM_CONFIGS);
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("planner.highways"), std::string::npos) << e.what();
  }
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/large_warehouse_agv.yaml");
  c.output.dir = test::temp_dir("ctl_highways");
  c.run.progress_s = 0;
  c.run.executor = "lockstep";
  c.run.max_ticks = 600;
  c.delays = DelaysSection{};
  c.fleet.seed = 2;
  c.tasks.seed = 3;
  c.planner.budget_ms = 0;  // deterministic: expansions per SUMO step
  c.planner.expansions = 50;
  c.planner.highways = 1;
  Controller ctl(c);
  const Metrics m = ctl.run();
  EXPECT_EQ(m.error, "");
  EXPECT_TRUE(m.solved) << "makespan " << m.makespan;
  EXPECT_EQ(m.violations, 0);
  const auto& plan = ctl.plan();
  ASSERT_FALSE(plan.empty());
  EXPECT_EQ(planner::validate_plan(ctl.map().graph, plan.front(), plan.back(), plan, true), "");
  ctest_util::expect_no_sumo_collision(c.output.dir);
  std::printf("large warehouse, 200 AGVs, lock-step with planner.highways 1: makespan %lld\n",
              static_cast<long long>(m.makespan));
}
