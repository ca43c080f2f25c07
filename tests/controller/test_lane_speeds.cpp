// Lane speeds (issue 24) on the real SUMO: the small warehouse with its picking aisle c1
// (c1r0 - c1r1, 8 m) slowed to 0.25 m/s; the parallel aisles c0 and c2 stay at 1 m/s. An
// AGV from c1r0 to c1r1 goes straight up c1 (8 moves) or round through c0 or c2 (16 moves).
//  - planner.lane_costs: the slow aisle's cells cost ceil(1 / 0.25) = 4 in the planner's
//    distance tables (lane_costs.hpp), so the AGV goes round; without them, straight up.
//  - run.lane_speeds: lockstep stretches a step over the ticks its move needs on its lane
//    (Commander::lane_ticks): SUMO's fcd shows no AGV faster than 0.25 m/s on c1; without
//    it the AGV drives 1 m/s there.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "controller/config.hpp"
#include "controller/controller.hpp"
#include "controller/lane_costs.hpp"
#include "gridify/gridifier.hpp"
#include "controller_test_util.hpp"
#include "planner/validator.hpp"
#include "temp_path.hpp"

using namespace controller;

namespace {

constexpr double kSlow = 0.25;

// small_warehouse.yaml (or `base`) on a copy of its net with aisle c1's two lanes at kSlow,
// one AGV from c1r0 to c1r1.
Config slow_aisle_config(const std::string& name, const std::string& base = "small_warehouse.yaml")
{
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/" + base);
  c.output.dir = test::temp_dir("lane_speeds_" + name);
  c.run.progress_s = 0;
  c.run.max_ticks = 200;
  c.planner.budget_ms = 0;  // deterministic
  c.planner.expansions = 50;
  const std::string net = c.output.dir + "/slow_c1.net.xml";
  std::ifstream in(c.sumo.net);
  std::ofstream out(net);
  const std::regex slow_lane(R"re(<lane id="c1r[01]_c1r[01]_0"[^>]* speed=")re");
  int slowed = 0;
  for (std::string line; std::getline(in, line);) {
    if (std::regex_search(line, slow_lane)) {
      line = std::regex_replace(line, std::regex(R"(speed="1\.00")"), R"(speed="0.25")");
      ++slowed;
    }
    out << line << '\n';
  }
  EXPECT_EQ(slowed, 2) << "the small net's aisle c1 changed: fix the test";
  c.sumo.net = net;
  c.fleet.count = 1;
  c.fleet.random_starts = false;
  c.fleet.starts = {CellRef{-1, "c1r0", "", 0, "fleet.starts[0]"}};
  c.tasks.random_goals = false;
  c.tasks.goals = {CellRef{-1, "c1r1", "", 0, "tasks.goals[0]"}};
  return c;
}

// Whether the executed plan passed through aisle c1 (its interior cells).
bool used_slow_aisle(const Controller& ctl)
{
  const gridify::CellMap& map = ctl.map();
  for (const planner::Config& c : ctl.plan())
    for (planner::Vertex v : c) {
      const gridify::Cell& cell = map.cells[static_cast<size_t>(v)];
      if (cell.kind == gridify::CellKind::Aisle && map.aisles[static_cast<size_t>(cell.aisle)].lane_ab.rfind("c1r", 0) == 0 &&
          map.aisles[static_cast<size_t>(cell.aisle)].lane_ab.find("_c1r") != std::string::npos)
        return true;
    }
  return false;
}

// The fastest fcd speed of any AGV (or of AGV `id`) on aisle `aisle`'s lanes, and the
// number of such samples.
std::pair<double, long> top_speed_on(const std::string& dir, const std::string& aisle, const std::string& id = "")
{
  const std::string s = ctest_util::slurp(dir + "/fcd.xml");
  const std::regex re("<vehicle id=\"([^\"]+)\"[^>]* speed=\"([-0-9.e]+)\"[^>]* lane=\"(" + aisle + "r[01]_" + aisle +
                      "r[01]_0)\"");
  double top = 0;
  long n = 0;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), re); it != std::sregex_iterator(); ++it) {
    if (!id.empty() && (*it)[1] != id) continue;
    top = std::max(top, std::stod((*it)[2]));
    ++n;
  }
  return {top, n};
}
std::pair<double, long> top_speed_on_c1(const std::string& dir) { return top_speed_on(dir, "c1"); }

Metrics run_clean(const Config& c, Controller& ctl)
{
  const Metrics m = ctl.run();
  EXPECT_EQ(m.error, "");
  EXPECT_TRUE(m.solved);
  EXPECT_EQ(m.commands.jumps, 0);
  EXPECT_EQ(m.commands.resyncs, 0);
  const auto& plan = ctl.plan();
  EXPECT_EQ(planner::validate_plan(ctl.map().graph, plan.front(), plan.back(), plan, true), "");
  ctest_util::expect_no_sumo_collision(c.output.dir);
  return m;
}

}  // namespace

TEST(LaneCosts, SlowAisleCellsCostTheirSpeedRatio)
{
  const Config c = slow_aisle_config("costs_unit");
  gridify::GridifyOptions go;
  go.cell_length = c.grid.cell_length;
  const gridify::CellMap map = gridify::gridify(c.sumo.net, go);
  const std::vector<uint8_t> cost = lane_costs(map, 1.0);
  int slow = 0;
  for (size_t v = 0; v < cost.size(); ++v) {
    const gridify::Cell& cell = map.cells[v];
    const bool in_c1 = cell.kind == gridify::CellKind::Aisle && map.aisles[static_cast<size_t>(cell.aisle)].lane_ab.rfind("c1r", 0) == 0 &&
                       map.aisles[static_cast<size_t>(cell.aisle)].lane_ab.find("_c1r") != std::string::npos;
    EXPECT_EQ(cost[v], in_c1 ? 4 : 1) << "cell " << v;  // junction cells: their fastest lane
    slow += in_c1;
  }
  EXPECT_EQ(slow, 7);
  // AGVs no faster than the slow lane: every cell costs 1.
  for (uint8_t k : lane_costs(map, kSlow)) EXPECT_EQ(k, 1);
}

// With the lane costs the AGV goes round the slow aisle, and gets there sooner; without
// them it takes the slow aisle (shorter in moves).
TEST(LaneCosts, AgvsRouteViaTheFastAislesWithCostsAndTheSlowShorterOneWithout)
{
  Config on = slow_aisle_config("costs_on");
  Controller a(on);
  const Metrics ma = run_clean(on, a);
  EXPECT_FALSE(used_slow_aisle(a)) << "with lane costs the AGV took the slow aisle";
  EXPECT_EQ(ma.makespan, 16);  // round through c0 or c2 at a cell per tick
  EXPECT_EQ(ma.ticks, 16);     // 1 m/s lanes, 1 m cells, 1 s ticks: nothing stretched
  EXPECT_EQ(ma.lane_ticks, 0);
  EXPECT_GT(ma.costly_cells, 0);

  Config off = slow_aisle_config("costs_off");
  off.planner.lane_costs = false;
  Controller b(off);
  const Metrics mb = run_clean(off, b);
  EXPECT_TRUE(used_slow_aisle(b)) << "without lane costs the AGV went round (the test shows nothing)";
  EXPECT_EQ(mb.makespan, 8);  // 8 moves, each stretched to the slow lane's 4 ticks
  EXPECT_EQ(mb.costly_cells, 0);
  EXPECT_GT(mb.ticks, ma.ticks);
}

// The same with pibt-rot: its rotation distances count a forward move into a slow cell at
// the cell's cost (planner/rotation/rotation_dist.hpp). Guidance off, so that only the costs
// decide. 8 moves straight up c1 at 4 ticks each, or round at a cell per tick plus turns.
TEST(LaneCosts, PibtRotRoutesViaTheFastAislesWithCostsAndTheSlowShorterOneWithout)
{
  auto rotation = [](Config c) {
    c.planner.solver = "pibt-rot";
    c.planner.rotation.guidance = "none";
    return c;
  };
  Config on = rotation(slow_aisle_config("rot_costs_on"));
  Controller a(on);
  const Metrics ma = run_clean(on, a);
  EXPECT_FALSE(used_slow_aisle(a)) << "with lane costs pibt-rot took the slow aisle";
  EXPECT_EQ(ma.lane_ticks, 0);
  EXPECT_GT(ma.commands.quarter_turns, 0);  // round: it turned on its way

  Config off = rotation(slow_aisle_config("rot_costs_off"));
  off.planner.lane_costs = false;
  Controller b(off);
  const Metrics mb = run_clean(off, b);
  EXPECT_TRUE(used_slow_aisle(b)) << "without lane costs pibt-rot went round (the test shows nothing)";
  EXPECT_GT(mb.lane_ticks, 0);
  EXPECT_GT(mb.ticks, ma.ticks);  // the slow aisle is the slower way
}

// Lockstep keeps to the slow lane's speed (fcd: SUMO's own speeds, every step); without
// run.lane_speeds the AGV drives a cell per tick (1 m/s) on it.
TEST(LaneSpeeds, LockstepNeverExceedsASlowLanesSpeed)
{
  Config on = slow_aisle_config("lockstep_on");
  on.planner.lane_costs = false;  // through the slow aisle
  Controller a(on);
  const Metrics ma = run_clean(on, a);
  ASSERT_TRUE(used_slow_aisle(a));
  const auto [top_on, n_on] = top_speed_on_c1(on.output.dir);
  EXPECT_GT(n_on, 0);
  EXPECT_LE(top_on, kSlow + 1e-6);
  EXPECT_GT(top_on, kSlow - 1e-3);  // it does drive there, at the limit
  // 8 m at 0.25 m/s: the 7 moves in c1 and the one into c1r1 (on c1's lane) take 4 ticks each.
  EXPECT_EQ(ma.ticks, 32);
  EXPECT_EQ(ma.lane_ticks, 24);

  Config off = slow_aisle_config("lockstep_off");
  off.planner.lane_costs = false;
  off.run.lane_speeds = false;
  Controller b(off);
  const Metrics mb = run_clean(off, b);
  const auto [top_off, n_off] = top_speed_on_c1(off.output.dir);
  EXPECT_GT(n_off, 0);
  EXPECT_GT(top_off, 2 * kSlow) << "without lane speeds the AGV should drive a cell per tick";
  EXPECT_EQ(mb.ticks, 8);
  EXPECT_EQ(mb.lane_ticks, 0);
}

// Per AGV under adg and adg-follow (unlike lockstep, where the whole fleet waits for the
// slowest move): AGV 0 drives up the slow aisle c1 (lane costs off), AGV 1 up the parallel
// aisle c2 at 1 m/s at the same time. SUMO's fcd: AGV 0 never faster than 0.25 m/s on c1,
// AGV 1 at its vType's 1 m/s on c2, and AGV 1 at its goal long before AGV 0 (8 m at 1 m/s
// against 8 m at 0.25 m/s: over 8 s earlier). Lockstep, same two AGVs: AGV 1 keeps to 0.25 m/s too (the
// documented synchronous steps). Without run.lane_speeds AGV 0 drives c1 at 1 m/s.
TEST(LaneSpeeds, AdgCapsEachAgvAtItsOwnLaneWhileOthersDriveFullSpeed)
{
  auto two_agvs = [](const std::string& name, const std::string& executor, bool lane_speeds) {
    Config c = slow_aisle_config(name, "small_warehouse_agv.yaml");
    c.run.executor = executor;
    c.run.lane_speeds = lane_speeds;
    c.planner.lane_costs = false;  // AGV 0 through the slow aisle
    c.delays = {};
    c.fleet.count = 2;
    c.fleet.starts.push_back(CellRef{-1, "c2r0", "", 0, "fleet.starts[1]"});
    c.tasks.goals.push_back(CellRef{-1, "c2r1", "", 0, "tasks.goals[1]"});
    return c;
  };
  for (const std::string executor : {"adg-follow", "adg"}) {
    SCOPED_TRACE(executor);
    const Config on = two_agvs("per_agv_" + executor, executor, true);
    Controller a(on);
    const Metrics m = run_clean(on, a);
    ASSERT_TRUE(used_slow_aisle(a));
    const auto [slow, n_slow] = top_speed_on(on.output.dir, "c1", "agv0");
    const auto [fast, n_fast] = top_speed_on(on.output.dir, "c2", "agv1");
    EXPECT_GT(n_slow, 0);
    EXPECT_GT(n_fast, 0);
    EXPECT_LE(slow, kSlow + 1e-6);
    EXPECT_GT(fast, 0.95) << "AGV 1 on the 1 m/s aisle is held back by AGV 0's slow lane";
    ASSERT_EQ(m.goal_s.size(), 2u);
    EXPECT_GT(m.goal_s[0], 0);
    EXPECT_GT(m.goal_s[1], 0);
    EXPECT_LT(m.goal_s[1] + 8, m.goal_s[0]);  // measured 18.75 s against 32.4 s

    const Config off = two_agvs("per_agv_off_" + executor, executor, false);
    Controller b(off);
    run_clean(off, b);
    EXPECT_GT(top_speed_on(off.output.dir, "c1", "agv0").first, 2 * kSlow) << "lane speed ignored: it should drive 1 m/s";
  }
  const Config lock = two_agvs("per_agv_lockstep", "lockstep", true);
  Controller l(lock);
  run_clean(lock, l);
  EXPECT_LE(top_speed_on(lock.output.dir, "c2", "agv1").first, kSlow + 1e-6) << "lockstep: the fleet waits for the slowest move";
}

// run.max_ticks is the run's last tick even when a step is stretched over several: the
// 4-tick moves through the slow aisle are not started past it (a limit of 30 ended at 32).
TEST(LaneSpeeds, AStretchedStepNeverRunsPastTheTickLimit)
{
  Config c = slow_aisle_config("lockstep_limit");
  c.planner.lane_costs = false;  // through the slow aisle: 4 ticks per move
  c.run.max_ticks = 30;
  Controller a(c);
  const Metrics m = a.run();
  EXPECT_EQ(m.error, "");
  EXPECT_FALSE(m.solved);  // it needs 32
  EXPECT_LE(m.ticks, 30);
  EXPECT_GE(m.ticks, 27);
}
