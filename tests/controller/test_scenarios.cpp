// Every shipped scenario run to completion on the real SUMO 1.15, the bottleneck on which
// naive replanning livelocks, and a TraCI connection lost because the sumo process dies.
// ctest runs each TEST in its own process; every test writes into its own temp dir.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "controller/commander.hpp"
#include "controller/config.hpp"
#include "controller_test_util.hpp"
#include "controller/controller.hpp"
#include "controller/sumo_error.hpp"
#include "gridify/gridifier.hpp"
#include "controller/sumo_options.hpp"
#include "planner/validator.hpp"
#include "temp_path.hpp"

using namespace controller;
namespace fs = std::filesystem;

namespace {

std::string temp_dir(const std::string& name) { return test::temp_dir("scn_" + name); }

Config scenario(const std::string& yaml, const std::string& name)
{
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/" + yaml);
  c.output.dir = temp_dir(name);
  c.run.progress_s = 0;
  return c;
}

using ctest_util::slurp;

// A run that reached every goal exactly: no violation, no re-sync, no SUMO collision,
// teleport or arrival (any of those stops the run with an error), a valid executed plan.
void expect_exact_solved_run(const Config& cfg, const Controller& c, const Metrics& m)
{
  EXPECT_EQ(m.error, "");
  EXPECT_TRUE(m.solved);
  EXPECT_EQ(m.violations, 0);
  EXPECT_EQ(m.commands.resyncs, 0);
  EXPECT_EQ(m.commands.jumps, 0);
  EXPECT_LE(m.commands.max_error, 1e-6);
  const auto& plan = c.plan();
  ASSERT_FALSE(plan.empty());
  EXPECT_EQ(static_cast<long long>(plan.size()), m.ticks + 1);
  EXPECT_EQ(planner::validate_plan(c.map().graph, plan.front(), plan.back(), plan, true), "");
  const nlohmann::json j = nlohmann::json::parse(slurp(cfg.output.dir + "/metrics.json"));
  EXPECT_EQ(j["solved"], true);
  EXPECT_EQ(j["ticks"], m.ticks);
  if (cfg.sumo.outputs.collision) {
    ctest_util::expect_no_sumo_collision(cfg.output.dir);
  }
  if (cfg.sumo.outputs.summary) {
    // SUMO's own count: nobody arrived or teleported, all AGVs still running at the end.
    const std::string s = slurp(cfg.output.dir + "/summary.xml");
    const size_t last = s.rfind("<step ");
    ASSERT_NE(last, std::string::npos);
    const std::string step = s.substr(last, s.find("/>", last) - last);
    EXPECT_NE(step.find(" arrived=\"0\""), std::string::npos) << step;
    EXPECT_NE(step.find(" teleports=\"0\""), std::string::npos) << step;
    EXPECT_NE(step.find(" collisions=\"0\""), std::string::npos) << step;
    EXPECT_NE(step.find(" running=\"" + std::to_string(m.agents) + "\""), std::string::npos) << step;
  }
}

// A TCP port nobody listens on right now.
int free_port()
{
  int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(s);
  return ntohs(a.sin_port);
}

// Starts `sumo <args> --remote-port <port>` as our own child (quiet), returns its pid.
pid_t spawn_sumo(std::vector<std::string> args, int port, const std::string& log)
{
  args.insert(args.begin(), "sumo");
  args.insert(args.end(), {"--remote-port", std::to_string(port)});
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::FILE* f = std::freopen(log.c_str(), "w", stdout);
    (void)f;
    ::dup2(::fileno(stdout), 2);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execvp("sumo", argv.data());
    ::_exit(127);
  }
  return pid;
}

// A scenario config set up to connect over TraCI to a sumo the test starts itself.
struct ExternalSumo {
  pid_t pid = -1;
  int port = 0;
  ExternalSumo(Config& cfg)
  {
    port = free_port();
    cfg.run.backend = "traci";
    cfg.run.port = port;
    const std::string vtype = write_vtype_file(cfg, cfg.output.dir, cfg.grid.cell_length);
    pid = spawn_sumo(sumo_args(cfg, cfg.output.dir, vtype, false), port, cfg.output.dir + "/sumo.log");
  }
  void kill()
  {
    if (pid <= 0) return;
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    pid = -1;
  }
  ~ExternalSumo() { kill(); }
};

}  // namespace

TEST(ControllerScenario, SmallWarehouseCompletesExactly)
{
  Config cfg = scenario("small_warehouse.yaml", "small");
  Controller c(cfg);
  const Metrics m = c.run();
  expect_exact_solved_run(cfg, c, m);
  EXPECT_EQ(m.agents, 16);
}

// "" when every move of the executed plan follows an arc of g (else the first that does
// not); `one_way` counts the moves whose reverse is no arc.
template <class Plan>
std::string moves_along_arcs(const planner::Graph& g, const Plan& plan, long long& one_way)
{
  for (size_t t = 1; t < plan.size(); ++t)
    for (size_t i = 0; i < plan[t].size(); ++i)
      if (plan[t][i] != plan[t - 1][i]) {
        if (!g.adjacent(plan[t - 1][i], plan[t][i]))
          return "t " + std::to_string(t) + " agent " + std::to_string(i) + ": no arc " + std::to_string(plan[t - 1][i]) +
                 " -> " + std::to_string(plan[t][i]);
        one_way += !g.adjacent(plan[t][i], plan[t - 1][i]);
      }
  return "";
}

// One-way picking aisles (issue 24): gridify keeps them as arcs, RT-LaCAM drives along
// them only forwards, SUMO reports no collision, every AGV ends exactly on its goal.
// Fails if the aisles were made two-way (no one-way arc) or refused (gridify error).
TEST(ControllerScenario, OneWayWarehouseCompletesExactly)
{
  Config cfg = scenario("small_oneway.yaml", "oneway");
  cfg.planner.budget_ms = 0;  // deterministic
  cfg.planner.expansions = 100;
  Controller c(cfg);
  const Metrics m = c.run();
  expect_exact_solved_run(cfg, c, m);
  EXPECT_EQ(m.agents, 10);
  const planner::Graph& g = c.map().graph;
  ASSERT_TRUE(g.directed());
  long long one_way_moves = 0;
  ASSERT_EQ(moves_along_arcs(g, c.plan(), one_way_moves), "");
  EXPECT_GT(one_way_moves, 16);
}

// The rotation solvers on the one-way warehouse (lifelong): AGVs with a heading drive the
// one-way aisles only forwards (every planned move is an arc of the directed graph), turn on
// their cells, and finish errands; 0 violations. Fails if the rotation planners refuse
// directed graphs (or the one-way lanes get no heading), or move against an arc.
TEST(ControllerScenario, RotationSolversDriveOneWayAislesForwardsOnly)
{
  for (const char* solver : {"pibt-rot", "wppl"}) {
    Config cfg = scenario("small_oneway_lifelong.yaml", std::string("oneway_rot_") + solver);
    cfg.planner.solver = solver;
    cfg.run.max_ticks = 150;
    Controller c(cfg);
    const Metrics m = c.run();
    ASSERT_EQ(m.error, "") << solver;
    EXPECT_EQ(m.violations, 0) << solver;
    EXPECT_GT(m.errands_finished, 0) << solver;
    const planner::Graph& g = c.map().graph;
    ASSERT_TRUE(g.directed());
    long long one_way_moves = 0;
    ASSERT_EQ(moves_along_arcs(g, c.plan(), one_way_moves), "") << solver;
    EXPECT_GT(one_way_moves, 10) << solver;
  }
}

TEST(ControllerScenario, LargeWarehouseHundredsOfAgvsCompleteExactly)
{
  Config cfg = scenario("large_warehouse.yaml", "large");
  cfg.planner.budget_ms = 0;  // deterministic
  cfg.planner.expansions = 20;
  cfg.planner.refine = true;  // the default: RT-LaCAM* (LNS charged against the expansions budget)
  Controller c(cfg);
  const Metrics m = c.run();
  expect_exact_solved_run(cfg, c, m);
  EXPECT_EQ(m.agents, 200);
  EXPECT_GT(m.commands.total(), 1000);
}

TEST(ControllerScenario, HugeWarehouseThousandAgvsCompleteExactly)
{
  // The benchmark scenario as a test: 1000 AGVs, 4680 cells, ~410 ticks, every AGV exact on
  // its goal. One SUMO step per tick (step_length = tick_s: scheme S is exact at any whole
  // k, SchemeS.PositionsExactOverManyTicks covers k = 8) cuts SUMO's share 8x: 53 s -> 10.5 s
  // under a load of 8-10 (2026-11-26); the same 40 expansions per tick as 5 x 8 steps.
  Config cfg = scenario("huge_warehouse.yaml", "huge");
  cfg.sumo.outputs = {false, false, true, true};
  cfg.sumo.step_length = cfg.run.tick_s;
  cfg.planner.budget_ms = 0;  // deterministic
  cfg.planner.expansions = 40;
  cfg.planner.refine = true;  // the default: RT-LaCAM* (LNS charged against the expansions budget)
  Controller c(cfg);
  const Metrics m = c.run();
  expect_exact_solved_run(cfg, c, m);
  EXPECT_EQ(m.agents, 1000);
  EXPECT_GT(m.cells, 4000);
}

TEST(ControllerScenario, BottleneckRtLacamPassesTheCorridor)
{
  for (uint64_t seed : {0, 1, 2}) {
    SCOPED_TRACE(seed);
    Config cfg = scenario("bottleneck.yaml", "bottleneck_rt" + std::to_string(seed));
    cfg.planner.seed = seed;
    ASSERT_EQ(cfg.planner.solver, "rtlacam");
    Controller c(cfg);
    const Metrics m = c.run();
    expect_exact_solved_run(cfg, c, m);
    EXPECT_EQ(m.agents, 8);
    EXPECT_LT(m.ticks, 300);
    // Everybody swapped ends: the corridor had to be shared.
    EXPECT_GE(m.soc, m.soc_lb);
  }
}

TEST(ControllerScenario, BottleneckNaiveReplanningStalls)
{
  // Same budget (2 expansions per SUMO step) as RT-LaCAM above: a fresh search every tick
  // never gets the two groups past each other. Still every executed step is valid.
  for (uint64_t seed : {0, 1, 2}) {
    SCOPED_TRACE(seed);
    Config cfg = scenario("bottleneck.yaml", "bottleneck_naive" + std::to_string(seed));
    cfg.planner.solver = "naive";
    cfg.planner.seed = seed;
    cfg.run.max_ticks = 1000;
    Controller c(cfg);
    const Metrics m = c.run();
    EXPECT_EQ(m.error, "");
    EXPECT_FALSE(m.solved);
    EXPECT_EQ(m.ticks, 1000);
    EXPECT_EQ(m.violations, 0);
    EXPECT_EQ(m.commands.resyncs, 0);
    EXPECT_LE(m.commands.max_error, 1e-6);
    EXPECT_EQ(planner::validate_plan(c.map().graph, c.plan().front(), c.plan().front(), c.plan(), false), "");
  }
}

TEST(ControllerScenario, ShippedConfigsAndSumocfgsLoad)
{
  // Every scenario has a config and a .sumocfg that SUMO accepts (sumo-gui -c uses it).
  for (const char* s : {"small", "small_oneway", "large", "huge", "bottleneck"}) {
    const std::string cfgfile = std::string(RTLACAM_SCENARIOS) + "/" + s + ".sumocfg";
    ASSERT_TRUE(fs::exists(cfgfile)) << cfgfile;
    const std::string log = temp_dir(std::string("sumocfg_") + s) + "/sumo.log";
    const std::string cmd = "sumo -c " + cfgfile + " --end 1 --no-step-log true > " + log + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(log);
  }
  for (const char* y : {"small_warehouse.yaml", "small_oneway.yaml", "small_oneway_lifelong.yaml", "large_warehouse.yaml",
                        "huge_warehouse.yaml", "bottleneck.yaml"}) {
    Config c = load_config(std::string(RTLACAM_CONFIGS) + "/" + y);
    EXPECT_TRUE(fs::exists(c.sumo.net)) << y;
  }
}

TEST(ControllerFault, SumoProcessKilledMidRun)
{
  // The test starts sumo itself (--remote-port), the controller connects over TraCI, and
  // the sumo process is killed at tick 5: one clear error line, metrics so far written.
  Config cfg = scenario("small_warehouse.yaml", "killed");
  cfg.planner.budget_ms = 0;
  cfg.planner.expansions = 20;
  ExternalSumo sumo(cfg);
  Controller c(cfg);
  c.on_tick = [&](long long tick, SumoBackend&) {
    if (tick == 5) sumo.kill();
  };
  const Metrics m = c.run();
  EXPECT_NE(m.error.find("connection lost"), std::string::npos) << m.error;
  EXPECT_EQ(m.error.rfind("SUMO ", 0), 0u) << m.error;
  EXPECT_EQ(m.error.find('\n'), std::string::npos) << m.error;
  EXPECT_FALSE(m.solved);
  EXPECT_EQ(m.ticks, 5);
  const nlohmann::json j = nlohmann::json::parse(slurp(cfg.output.dir + "/metrics.json"));
  EXPECT_EQ(j["error"], m.error);
  EXPECT_EQ(j["ticks"], 5);
  EXPECT_EQ(j["solved"], false);
  EXPECT_TRUE(fs::exists(cfg.output.dir + "/plan.txt"));
}

TEST(ControllerFault, SumoProcessKilledUnderTheAppExitsNonZero)
{
  // The same through the CLI: rtlacam-sumo --port P against our sumo, killed once the
  // app has printed its first progress line.
  Config cfg = scenario("large_warehouse.yaml", "killed_app");
  cfg.sumo.outputs = {false, false, false, false};
  ExternalSumo sumo(cfg);
  const std::string yaml = cfg.output.dir + "/run.yaml";
  std::ofstream(yaml) << "sumo:\n  net: " << cfg.sumo.net << "\n  outputs: {fcd: false, tripinfo: false, summary: false, collision: false}\n"
                      << "fleet: {count: 200, seed: 1}\ntasks: {seed: 2}\nrun: {progress_s: 0.05}\n";
  const std::string cmd = std::string(RTLACAM_SUMO_APP) + " " + yaml + " --port " + std::to_string(sumo.port) +
                          " --out " + cfg.output.dir + " 2>&1";
  std::FILE* app = ::popen(cmd.c_str(), "r");
  ASSERT_NE(app, nullptr);
  std::string out;
  char line[4096];
  while (std::fgets(line, sizeof line, app)) {
    out += line;
    if (std::string(line).rfind("[rtlacam-sumo] tick", 0) == 0) sumo.kill();
  }
  const int status = ::pclose(app);
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 1) << out;
  EXPECT_NE(out.find("error: SUMO "), std::string::npos) << out;
  EXPECT_NE(out.find("connection lost"), std::string::npos) << out;
  const nlohmann::json j = nlohmann::json::parse(slurp(cfg.output.dir + "/metrics.json"));
  EXPECT_NE(j["error"].get<std::string>(), "");
  EXPECT_GT(j["ticks"].get<long long>(), 0);
  EXPECT_EQ(j["solved"], false);
}

TEST(ControllerFault, AgvRemovedOverTraciIsCaught)
{
  // Over TraCI the poses come from one context subscription per tick: an AGV missing
  // from it is reported like any other lost AGV.
  Config cfg = scenario("small_warehouse.yaml", "removed_traci");
  cfg.run.backend = "traci";
  cfg.planner.budget_ms = 0;
  cfg.planner.expansions = 20;
  Controller c(cfg);
  c.on_tick = [](long long tick, SumoBackend& sumo) {
    if (tick == 4) sumo.remove("agv7");
  };
  const Metrics m = c.run();
  EXPECT_NE(m.error.find("agv7"), std::string::npos) << m.error;
  EXPECT_NE(m.error.find("removed behind the controller's back"), std::string::npos) << m.error;
  EXPECT_EQ(m.violations, 0);  // a vanished AGV is a runtime fault (exit 1), not a plan violation
  EXPECT_EQ(m.ticks, 4);
}

TEST(ControllerMetrics, JsonHasTheIssuesFields)
{
  Config cfg = scenario("small_warehouse.yaml", "metrics");
  Controller c(cfg);
  const Metrics m = c.run();
  ASSERT_EQ(m.error, "");
  const nlohmann::json j = nlohmann::json::parse(slurp(cfg.output.dir + "/metrics.json"));
  for (const char* k : {"ticks", "solved", "soc", "makespan", "violations", "resyncs", "error", "ms_per_sim_s",
                        "controller_to_sumo_ratio", "real_time_factor"})
    EXPECT_TRUE(j.contains(k)) << k;
  for (const char* k : {"p50", "p99", "max", "mean", "count"}) EXPECT_TRUE(j["planner_ms_per_step"].contains(k)) << k;
  EXPECT_EQ(j["commands"]["total"], m.commands.total());
  EXPECT_GT(j["commands"]["total"].get<long long>(), 0);
  for (const char* k : {"wall", "sumo", "controller", "planner", "control"}) EXPECT_TRUE(j["ms_per_sim_s"].contains(k)) << k;
  EXPECT_GT(j["ms_per_sim_s"]["sumo"].get<double>(), 0);
}

TEST(ControllerFault, AgvMissingAtVerificationIsNamed)
{
  // An AGV gone when verify() reads the poses (no arrival check in between): verify()
  // itself names it, with libsumo (per-AGV getters) and TraCI (context subscription).
  for (const char* backend : {"libsumo", "traci"}) {
    SCOPED_TRACE(backend);
    Config cfg = scenario("small_warehouse.yaml", std::string("missing_") + backend);
    cfg.sumo.outputs = {false, false, false, false};
    const gridify::CellMap map = gridify::gridify(cfg.sumo.net);
    std::unique_ptr<SumoBackend> sumo = std::string(backend) == "traci" ? make_traci_backend() : make_libsumo_backend();
    Commander cmd(map, *sumo, cfg.run.tick_s);
    sumo->start(sumo_args(cfg, cfg.output.dir, write_vtype_file(cfg, cfg.output.dir, 1.0), false));
    const planner::Config at{0, 5, 10, 15};
    cmd.insert(at);
    sumo->step();
    cmd.verify(at, 1e-6);
    sumo->remove("agv2");
    sumo->request_poses();
    sumo->step();
    try {
      cmd.verify(at, 1e-6);
      ADD_FAILURE() << "no error";
    } catch (const FleetError& e) {
      EXPECT_NE(std::string(e.what()).find("AGV agv2 (agent 2)"), std::string::npos) << e.what();
    }
    sumo->close();
  }
}

// The README's external-SUMO recipe: `sumo --remote-port P -n NET` knows no `agv` vType,
// no stations and no outputs; the controller reloads it with the run's options, so the run
// completes exactly and the configured outputs are written (not silently dropped).
TEST(ControllerScenario, ExternalSumoStartedBareRunsTheConfiguredSimulation)
{
  Config cfg = scenario("small_warehouse.yaml", "external_bare");
  const int port = free_port();
  cfg.run.backend = "traci";
  cfg.run.port = port;
  const pid_t pid = spawn_sumo({"-n", cfg.sumo.net}, port, cfg.output.dir + "/sumo.log");
  ASSERT_GT(pid, 0);
  Controller c(cfg);
  const Metrics m = c.run();
  // The controller's close ends that SUMO, which writes its outputs and exits by itself.
  int status = 0;
  pid_t done = 0;
  for (int i = 0; i < 200 && done == 0; ++i) {
    done = ::waitpid(pid, &status, WNOHANG);
    if (done == 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (done == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  }
  ASSERT_EQ(done, pid) << "the external SUMO did not exit after the run";
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << slurp(cfg.output.dir + "/sumo.log");
  expect_exact_solved_run(cfg, c, m);
  for (const char* f : {"fcd.xml", "tripinfo.xml", "summary.xml", "collision.xml"})
    EXPECT_TRUE(fs::exists(cfg.output.dir + "/" + f)) << f << " not written by the external SUMO";
  EXPECT_NE(slurp(cfg.output.dir + "/fcd.xml").find("<vehicle id="), std::string::npos);
}

// The stations file goes to SUMO with the vType (sumo-gui draws it).
TEST(ControllerScenario, SumoGetsTheStationsFile)
{
  Config cfg = scenario("small_warehouse.yaml", "stations_arg");
  ASSERT_FALSE(cfg.sumo.additional.empty());
  const std::vector<std::string> a = sumo_args(cfg, cfg.output.dir, "agv.add.xml", false);
  auto it = std::find(a.begin(), a.end(), "-a");
  ASSERT_NE(it, a.end());
  EXPECT_EQ(*(it + 1), "agv.add.xml," + cfg.sumo.additional);
}

// --gui without a display: one line "cannot open display", at once (no TraCI retries).
TEST(ControllerScenario, GuiWithoutDisplayIsOneLineAtOnce)
{
  Config cfg = scenario("small_warehouse.yaml", "nodisplay");
  for (const char* display : {"", ":97"}) {  // unset; a display no X server serves
    const std::string cmd = std::string(display[0] ? "DISPLAY=" : "env -u DISPLAY") + display + " " +
                            RTLACAM_SUMO_APP + " " + cfg.path + " --gui --out " + cfg.output.dir + " 2>&1";
    const auto t0 = std::chrono::steady_clock::now();
    std::FILE* app = ::popen(cmd.c_str(), "r");
    ASSERT_NE(app, nullptr);
    std::string out;
    char line[4096];
    while (std::fgets(line, sizeof line, app)) out += line;
    const int status = ::pclose(app);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(WIFEXITED(status)) << out;
    EXPECT_EQ(WEXITSTATUS(status), 1) << out;
    EXPECT_NE(out.find("cannot open display"), std::string::npos) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
    EXPECT_LT(s, 5.0) << out;
  }
}
