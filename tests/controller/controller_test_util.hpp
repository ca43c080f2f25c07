#pragma once
// Helpers shared by the controller tests: the first config error of a YAML text, a whole
// file as a string, "SUMO itself recorded no collision" for a run's output dir, and the
// shipped lifelong AGV config with the checks every physics run must pass.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "controller/metrics.hpp"
#include "temp_path.hpp"

namespace ctest_util {

inline std::string slurp(const std::string& path)
{
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The message of the ConfigError the YAML raises ("(no error)" when it parses).
inline std::string config_error(const std::string& yaml)
{
  try {
    controller::parse_config(yaml, "t.yaml", RTLACAM_CONFIGS);
  } catch (const controller::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

inline void expect_no_sumo_collision(const std::string& out_dir)
{
  EXPECT_EQ(slurp(out_dir + "/collision.xml").find("<collision "), std::string::npos) << out_dir;
}

// A shipped config (config/`file`) for a test: quiet, `ticks` long (0: the config's), SUMO writing
// only its collision output (into a fresh scratch dir `name`), and with `expansions` > 0 a budget
// of that many expansions per SUMO step and no clock, so that the run is deterministic.
inline controller::Config shipped_config(const std::string& file, const std::string& name, long long ticks,
                                         int expansions = 0)
{
  controller::Config cfg = controller::load_config(std::string(RTLACAM_CONFIGS) + "/" + file);
  cfg.output.dir = test::temp_dir(name);
  cfg.run.progress_s = 0;
  if (ticks > 0) cfg.run.max_ticks = ticks;
  if (expansions > 0) {
    cfg.planner.budget_ms = 0;
    cfg.planner.expansions = expansions;
  }
  cfg.sumo.outputs = {false, false, false, true};
  return cfg;
}

// The planner a scenario test's situation was found with, before session 44 (planner.free_first
// off, no startup planning). A test whose mechanism shows only in a particular run -- an AGV
// that runs empty, a wedged stub, a passing stop, an out-and-back -- pins it: the defaults
// since plan those runs differently, and often the situation does not arise at all.
inline void planner_before_s44(controller::Config& cfg)
{
  cfg.planner.free_first = false;
  cfg.planner.startup_ticks = 0;
}

// config/small_warehouse_lifelong_agv.yaml, `ticks` long (shipped_config).
inline controller::Config lifelong_agv_config(const std::string& name, long long ticks)
{
  return shipped_config("small_warehouse_lifelong_agv.yaml", name, ticks);
}

// A run Safety checked after every SUMO step that nothing stopped: no error, no violation,
// no moveTo jump or re-sync, and no collision in SUMO's own output.
inline void expect_checked_every_step(const controller::Config& cfg, const controller::Metrics& m)
{
  EXPECT_EQ(m.error, "");
  EXPECT_EQ(m.violations, 0);
  EXPECT_EQ(m.commands.jumps + m.commands.resyncs, 0);
  EXPECT_EQ(m.safety_checks, m.ticks * cfg.steps_per_tick());
  expect_no_sumo_collision(cfg.output.dir);
}

// Runs `cfg` to its end and expects it checked every step (above); its metrics.
inline controller::Metrics run_checked(const controller::Config& cfg)
{
  controller::Controller c(cfg);
  const controller::Metrics m = c.run();
  expect_checked_every_step(cfg, m);
  return m;
}

}  // namespace ctest_util
