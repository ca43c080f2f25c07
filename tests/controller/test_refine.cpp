// planner.refine in the controller: the YAML key (default on), and a real SUMO run of the
// small warehouse with RT-LaCAM* against the paper's RT-LaCAM (deterministic budgets).
#include <gtest/gtest.h>

#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "controller_test_util.hpp"
#include "planner/validator.hpp"
#include "temp_path.hpp"

using namespace controller;

namespace {

const std::string kNet = "sumo:\n  net: ../sumo_scenarios/small.net.xml\n";

// libsumo holds one simulation per process: the second run of a test goes through TraCI.
Metrics run_small(bool refine, const std::string& backend)
{
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse.yaml");
  c.output.dir = test::temp_dir(refine ? "ctl_refine_on" : "ctl_refine_off");
  c.run.progress_s = 0;
  c.planner.budget_ms = 0;  // deterministic: expansions per SUMO step
  c.planner.expansions = 20;
  c.planner.refine = refine;
  c.run.backend = backend;
  Controller ctl(c);
  Metrics m = ctl.run();
  const auto& plan = ctl.plan();
  EXPECT_FALSE(plan.empty());
  if (!plan.empty()) {
    EXPECT_EQ(planner::validate_plan(ctl.map().graph, plan.front(), plan.back(), plan, true), "");
  }
  ctest_util::expect_no_sumo_collision(c.output.dir);
  return m;
}

}  // namespace

TEST(ControllerRefine, YamlKeyDefaultsOnAndParses)
{
  EXPECT_TRUE(parse_config(kNet + "fleet: {count: 3}\n", "t.yaml", RTLACAM_CONFIGS).planner.refine);
  EXPECT_FALSE(
      parse_config(kNet + "fleet: {count: 3}\nplanner: {refine: false}\n", "t.yaml", RTLACAM_CONFIGS).planner.refine);
  EXPECT_THROW(parse_config(kNet + "fleet: {count: 3}\nplanner: {refine: maybe}\n", "t.yaml", RTLACAM_CONFIGS),
               std::exception);
}

TEST(ControllerRefine, SmallWarehouseRefinedRunIsCleanAndNoCostlier)
{
  const Metrics on = run_small(true, "libsumo");
  const Metrics off = run_small(false, "traci");
  for (const Metrics* m : {&on, &off}) {
    EXPECT_EQ(m->error, "");
    EXPECT_TRUE(m->solved);
    EXPECT_EQ(m->violations, 0);
  }
  EXPECT_LT(on.soc, off.soc) << "refinement should shorten the default demo";
}
