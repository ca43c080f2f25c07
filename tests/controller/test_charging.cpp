// Charging (issue 24, tasks/battery.hpp) on the real SUMO: the shipped warehouse with four
// dead-end charger stubs (sumo_scenarios/small_charging, config/small_charging_lifelong.yaml).
// AGVs drain per metre and per turn; below the threshold between tasks each takes a
// charging errand to the nearest free chargingStation, stands there charging at the
// station's power and goes back to work at the target. With charging switched off
// (fleet.battery.charging: false) the same fleet runs empty.
#include <gtest/gtest.h>

#include <libsumo/libsumo.h>

#include <algorithm>
#include <map>

#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "controller_test_util.hpp"

using namespace controller;

namespace {

// The shipped config, shortened for a test: 8 AGVs starting at 40 %, a faster drain, 300
// ticks, a deterministic 50 expansions per SUMO step.
Config charging_config(const std::string& name, const std::string& assignment, bool charging)
{
  Config cfg = ctest_util::shipped_config("small_charging_lifelong.yaml", "charging_" + name, 300, 50);
  cfg.fleet.count = 8;
  cfg.fleet.battery.initial = 0.4;
  cfg.fleet.battery.per_m_wh = 0.2;
  cfg.fleet.battery.charging = charging;
  cfg.tasks.assignment = assignment;
  return cfg;
}

// Per AGV, the longest run of ticks it stood at the end of a charger stub, read from SUMO.
struct ChargerWatch {
  std::map<std::string, int> run, longest;
  void operator()(long long, SumoBackend&)
  {
    for (const std::string& v : libsumo::Vehicle::getIDList()) {
      const std::string lane = libsumo::Vehicle::getLaneID(v);
      const bool on = lane.find("_chg") != std::string::npos && libsumo::Vehicle::getLanePosition(v) > 1.5;
      run[v] = on ? run[v] + 1 : 0;
      longest[v] = std::max(longest[v], run[v]);
    }
  }
  int agvs_that_charged(int ticks) const
  {
    return static_cast<int>(std::count_if(longest.begin(), longest.end(), [&](const auto& kv) { return kv.second >= ticks; }));
  }
};

void expect_charged_and_worked(const Config& cfg, const Metrics& m, const ChargerWatch& w)
{
  ctest_util::expect_checked_every_step(cfg, m);
  const Metrics::BatteryStats& b = m.battery;
  ASSERT_TRUE(b.active);
  EXPECT_EQ(b.ran_empty, 0);
  EXPECT_GT(b.min_charge, 0.0);
  EXPECT_GE(b.errands, cfg.fleet.count);  // every AGV went to charge at least once
  EXPECT_GT(b.charging_share, 0.05);
  // 0.4 -> 0.9 of 100 Wh at 1.9 Wh per tick is about 26 ticks on a charger: SUMO saw
  // AGVs standing at the chargers that long.
  EXPECT_GE(w.agvs_that_charged(20), cfg.fleet.count / 2);
  // Sampled every 10 ticks; someone left at the target and went back to work.
  ASSERT_EQ(b.samples.size(), static_cast<size_t>(m.ticks / 10));
  double top = 0;
  for (const auto& s : b.samples) top = std::max(top, s.max);
  EXPECT_GE(top, cfg.fleet.battery.target - 0.02);
  EXPECT_GT(m.errands_finished, 40);
}

}  // namespace

TEST(Charging, LowAgvsChargeAndNoneRunsEmptyPool)
{
  Config cfg = charging_config("pool", "pool", true);
  Controller c(cfg);
  ChargerWatch w;
  c.on_tick = [&](long long t, SumoBackend& s) { w(t, s); };
  const Metrics m = c.run();
  expect_charged_and_worked(cfg, m, w);

  // Charging off: the same fleet and tasks drain to 0.
  Config off = charging_config("pool_off", "pool", false);
  Controller co(off);
  const Metrics mo = co.run();
  ctest_util::expect_checked_every_step(off, mo);
  EXPECT_GT(mo.battery.ran_empty, 0);
  EXPECT_EQ(mo.battery.errands, 0);
  EXPECT_EQ(mo.battery.min_charge, 0.0);
}

TEST(Charging, RoundRobinAgvsGetTheirNextTaskAfterCharging)
{
  Config cfg = charging_config("rr", "roundrobin", true);
  Controller c(cfg);
  ChargerWatch w;
  c.on_tick = [&](long long t, SumoBackend& s) { w(t, s); };
  const Metrics m = c.run();
  expect_charged_and_worked(cfg, m, w);

  Config off = charging_config("rr_off", "roundrobin", false);
  Controller co(off);
  EXPECT_GT(co.run().battery.ran_empty, 0);
}

TEST(Charging, BadBatteryInputIsOneLineErrors)
{
  const std::string head = "sumo: {net: ../sumo_scenarios/small_charging.net.xml, additional: ../sumo_scenarios/small_charging.add.xml}\n"
                           "fleet:\n  count: 2\n  battery: ";
  const std::string lifelong = "\ntasks: {mode: lifelong}\n";
  std::string e = ctest_util::config_error(head + "{threshold: 0.9, target: 0.5}" + lifelong);
  EXPECT_NE(e.find("fleet.battery.threshold: must be < target (0.5), got 0.9"), std::string::npos) << e;
  e = ctest_util::config_error(head + "{target: 1.5}" + lifelong);
  EXPECT_NE(e.find("fleet.battery.target: is a fraction of capacity_wh"), std::string::npos) << e;
  e = ctest_util::config_error(head + "{capacity_wh: 0}" + lifelong);
  EXPECT_NE(e.find("fleet.battery.capacity_wh: must be > 0"), std::string::npos) << e;
  e = ctest_util::config_error(head + "{volts: 24}" + lifelong);
  EXPECT_NE(e.find("fleet.battery.volts: unknown key"), std::string::npos) << e;
  e = ctest_util::config_error(head + "{capacity_wh: 10}\n");
  EXPECT_NE(e.find("fleet.battery: only with tasks.mode: lifelong"), std::string::npos) << e;

  auto run_error = [](Config cfg) -> std::string {
    try {
      Controller c(cfg);
      c.run();
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  };
  // No chargingStation in the additional file.
  Config cfg = charging_config("bad_none", "pool", true);
  cfg.sumo.net = std::string(RTLACAM_CONFIGS) + "/../sumo_scenarios/small.net.xml";
  cfg.sumo.additional = std::string(RTLACAM_CONFIGS) + "/../sumo_scenarios/small.add.xml";
  e = run_error(cfg);
  EXPECT_NE(e.find("fleet.battery: charging is on, but sumo.additional has no chargingStation"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos);
  // A chargingStation without power, and no fleet.battery.charge_w.
  cfg = charging_config("bad_power", "pool", true);
  std::string add = ctest_util::slurp(cfg.sumo.additional);
  const std::string attr = R"( power="7200")";
  add.erase(add.find(attr), attr.size());
  cfg.sumo.additional = test::temp_file("nopower.add.xml", add);
  e = run_error(cfg);
  EXPECT_NE(e.find("fleet.battery: chargingStation 'charger_b0' has no power attribute and fleet.battery.charge_w is not set"),
            std::string::npos)
      << e;
  cfg.fleet.battery.charge_w = 3600;  // then the default power serves
  cfg.run.max_ticks = 2;
  EXPECT_EQ(run_error(cfg), "(no error)");
}

// Chargers sized against the fleet's drain (Run::prepare): with every AGV driving a move and
// a turn per tick, the fleet may drive away at most half of what the chargers give, else one
// warning line at the start. small_charging as shipped (16 AGVs, 0.1 Wh/m + 0.05 per turn:
// 2.4 Wh per tick against 7.6) runs without it; at 1 Wh/m (16.8 against 7.6) it warns. Large
// warehouse, 200 AGVs on 16 chargers at 0.1 Wh/m: 192 ran empty in 2000 ticks (s42).
TEST(Charging, ChargersShortOfTheFleetsDrainGetAStartUpWarning)
{
  for (double per_m : {0.1, 1.0}) {
    Config cfg = ctest_util::shipped_config("small_charging_lifelong.yaml", "charging_supply", 1, 50);
    cfg.fleet.battery.per_m_wh = per_m;
    testing::internal::CaptureStderr();
    Controller c(cfg);
    const Metrics m = c.run();
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(m.error, "");
    const bool warned = err.find("AGVs may run empty (size the chargers") != std::string::npos;
    EXPECT_EQ(warned, per_m > 0.5) << err;
  }
}
