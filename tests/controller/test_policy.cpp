// The learned policy in the controller (planner.policy, solver cspibt) on the real SUMO
// 1.15 through libsumo; ctest runs each TEST in its own process.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "planner/validator.hpp"
#include "temp_path.hpp"

using namespace controller;
namespace fs = std::filesystem;

namespace {

const std::string kModel = std::string(RTLACAM_POLICY_MODELS) + "/random-32-32-20.bin";

std::string temp_dir(const std::string& name) { return test::temp_dir("pol_" + name); }

Config small_config(const std::string& name, const std::string& solver)
{
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse.yaml");
  c.output.dir = temp_dir(name);
  c.run.progress_s = 0;
  c.planner.budget_ms = 0;
  c.planner.expansions = 20;
  c.planner.solver = solver;
  c.planner.policy = kModel;
  return c;
}

// Valid run: no violation, exact positions, the executed plan valid (to the goals if solved).
void expect_valid_run(const Controller& c, const Metrics& m)
{
  EXPECT_EQ(m.error, "");
  EXPECT_EQ(m.violations, 0);
  EXPECT_EQ(m.commands.resyncs, 0);
  EXPECT_LE(m.commands.max_error, 1e-6);
  const auto& plan = c.plan();
  ASSERT_FALSE(plan.empty());
  EXPECT_EQ(planner::validate_plan(c.map().graph, plan.front(), plan.back(), plan, false), "");
}

std::string run_error(Config c)
{
  try {
    Controller(c).run();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(ControllerPolicy, RtLacamWithPolicyReachesAllGoals)
{
  Config cfg = small_config("rtlacam", "rtlacam");
  Controller c(cfg);
  const Metrics m = c.run();
  expect_valid_run(c, m);
  EXPECT_TRUE(m.solved);
  EXPECT_EQ(m.policy, kModel);
  EXPECT_EQ(planner::validate_plan(c.map().graph, c.plan().front(), c.plan().back(), c.plan(), true), "");
  std::ifstream in(cfg.output.dir + "/metrics.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("random-32-32-20.bin"), std::string::npos);
}

TEST(ControllerPolicy, CspibtRunsValid)
{
  // CS-PIBT has no search: it may not reach every goal (the paper's Fig. 3); it must stay valid.
  Config cfg = small_config("cspibt", "cspibt");
  cfg.run.max_ticks = 300;
  Controller c(cfg);
  const Metrics m = c.run();
  expect_valid_run(c, m);
  EXPECT_GT(m.ticks, 0);
}

TEST(ControllerPolicy, LifelongWithPolicyServesTasks)
{
  Config cfg = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse_lifelong.yaml");
  cfg.output.dir = temp_dir("lifelong");
  cfg.run.progress_s = 0;
  cfg.run.max_ticks = 150;
  cfg.planner.budget_ms = 0;
  cfg.planner.expansions = 20;
  cfg.planner.policy = kModel;
  Controller c(cfg);
  const Metrics m = c.run();
  expect_valid_run(c, m);
  EXPECT_GT(m.errands_finished, 0);
}

TEST(ControllerPolicy, Errors)
{
  const std::string net = "sumo:\n  net: ../sumo_scenarios/small.net.xml\nfleet: {count: 3}\n";
  auto parse_error = [](const std::string& yaml) -> std::string {
    try {
      parse_config(yaml, "t.yaml", RTLACAM_CONFIGS);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(parse_error(net + "planner: {solver: cspibt}\n"),
            "t.yaml: planner.solver: cspibt needs planner.policy (a weights file)");
  EXPECT_EQ(parse_error(net + "planner: {policy: nowhere.bin}\n").rfind("t.yaml: planner.policy: file '", 0), 0u);
  EXPECT_EQ(parse_error(net + "planner: {policy: [a]}\n"), "t.yaml: planner.policy: expected a string");
  // Relative to the YAML file.
  const Config ok = parse_config(net + "planner: {solver: cspibt, policy: ../policy/models/random-32-32-20.bin}\n",
                                 "t.yaml", RTLACAM_CONFIGS);
  EXPECT_TRUE(fs::equivalent(ok.planner.policy, kModel));

  // A net whose cells are not on a lattice.
  Config diag = parse_config("sumo:\n  net: " + std::string(RTLACAM_CONTROLLER_DATA) +
                                 "/diagonal.net.xml\nfleet: {count: 2}\nplanner: {policy: " + kModel + "}\n",
                             "t.yaml", RTLACAM_CONFIGS);
  diag.output.dir = temp_dir("diag");
  EXPECT_EQ(run_error(diag).rfind("t.yaml: planner.policy: needs a net whose cells lie on a lattice", 0), 0u)
      << run_error(diag);
  // Without the policy the same net runs (the check is the policy's).
  diag.planner.policy.clear();
  diag.run.max_ticks = 3;
  EXPECT_EQ(run_error(diag), "(no error)");

  // A broken weights file: one line naming it.
  Config bad = parse_config(net, "t.yaml", RTLACAM_CONFIGS);
  bad.output.dir = temp_dir("bad");
  bad.planner.policy = bad.output.dir + "/bad.bin";
  std::ofstream(bad.planner.policy) << "RTLPOLCY truncated";
  const std::string e = run_error(bad);
  EXPECT_EQ(e.rfind("t.yaml: planner.policy: ", 0), 0u) << e;
  EXPECT_NE(e.find("bad.bin"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}
