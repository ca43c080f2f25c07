// rtlacam-lifelong end to end: the JSON log's fields, the default mode per round, exit
// codes and one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tasks_test_util.hpp"
#include "temp_path.hpp"

namespace {

struct CliRun {
  int code;
  std::string out, err;
};

CliRun run_cli(const std::string& args)
{
  const std::string o = test::temp_path("cli.out"), e = test::temp_path("cli.err");
  const int rc = std::system((std::string(RTLACAM_LIFELONG_BIN) + " " + args + " >" + o + " 2>" + e).c_str());
  auto slurp = [](const std::string& f) {
    std::ifstream in(f);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, slurp(o), slurp(e)};
}

}  // namespace

TEST(LifelongCli, RoundRobinLogHasTheLorrFields)
{
  const std::string log = test::temp_path("rr.json");
  const CliRun r = run_cli("--problem " + ttest::kData + "/2023/random.domain/MR23-I-04.json --steps 100 --solver rtlacam "
                    "--budget-ms 20 --budget-expansions 100 --seed 3 --quiet --out " + log);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(log);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["actionModel"], "MAPF");  // PlanViz's name for 4-connected moves
  EXPECT_EQ(j["teamSize"], 100);
  EXPECT_EQ(j["mode"], "roundrobin");
  EXPECT_EQ(j["assigner"], "none");
  EXPECT_EQ(j["solver"], "rtlacam");
  EXPECT_EQ(j["makespan"], 100);
  EXPECT_EQ(j["seed"], 3);
  EXPECT_EQ(j["numPlannerErrors"], 0);
  EXPECT_EQ(j["numTaskFinished"], j["numErrandFinished"]);
  EXPECT_EQ(j["version"], "2023 LoRR");
  ASSERT_EQ(j["events"].size(), 100u);  // LoRR 2023: per agent [task, t, "assigned" | "finished"]
  size_t finished = 0;
  for (const auto& ev : j["events"])
    for (const auto& e : ev) finished += e[2] == "finished";
  EXPECT_EQ(finished, j["numErrandFinished"].get<size_t>());
  EXPECT_DOUBLE_EQ(j["taskThroughput"].get<double>(), j["numTaskFinished"].get<double>() / 100.0);
  EXPECT_FALSE(j.contains("throughput"));  // one name per quantity
  for (const char* k : {"mean", "p50", "p99", "max"}) EXPECT_TRUE(j["plannerTimeStats"].contains(k)) << k;
  EXPECT_EQ(j["plannerTimes"].size(), 100u);  // LoRR: seconds per step
  EXPECT_EQ(j["actualPaths"].size(), 100u);
  // stdout: the same summary without events.
  const auto s = nlohmann::json::parse(r.out);
  EXPECT_FALSE(s.contains("events"));
  EXPECT_FALSE(s.contains("actualPaths"));
  EXPECT_EQ(s["numTaskFinished"], j["numTaskFinished"]);
}

TEST(LifelongCli, PoolIsTheDefaultFor2024AndStepsComeFromSimulationTime)
{
  const CliRun r = run_cli("--problem " + ttest::kData + "/2024/random.domain/RANDOM-01.json --solver pibt --assigner hungarian --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mode"], "pool");
  EXPECT_EQ(j["assigner"], "hungarian");
  EXPECT_EQ(j["makespan"], 600);
  EXPECT_EQ(j["numPlannerErrors"], 0);
}

TEST(LifelongCli, BadInputIsOneLineAndExitCode2)
{
  const std::string bad = ttest::temp_file("bad_problem.json", R"({"mapFile":"nope.map","agentFile":"a","taskFile":"t","teamSize":1})");
  const CliRun r = run_cli("--problem " + bad);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("nope.map"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(run_cli("--problem x.json --solver lacam").code, 0);
}

TEST(LifelongCli, AgentsUsesTheFirstNOfTheTeam)
{
  const std::string p = ttest::kData + "/2023/random.domain/MR23-I-04.json";
  const CliRun r = run_cli("--problem " + p + " --agents 20 --steps 30 --solver naive --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["teamSize"], 20);
  const CliRun bad = run_cli("--problem " + p + " --agents 101 --steps 30");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("teamSize is 100"), std::string::npos) << bad.err;
}

// The queues' clearing rules and the starvation guard reach the grid too (tasks.queues.clear_after,
// in_line, leavers_first; tasks.urgency.escalate_after); leavers first without clearing is a
// one-line error, as in the YAML.
TEST(LifelongCli, QueueClearingAndEscalationOptions)
{
  const std::string p = ttest::kData + "/2023/random.domain/MR23-I-04.json";
  const CliRun r = run_cli("--problem " + p + " --agents 20 --steps 30 --quiet --queue-capacity 1 --queue-clear-after 20 "
                           "--queue-in-line --queue-leavers-first --escalate-after 10");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["teamSize"], 20);
  const CliRun bad = run_cli("--problem " + p + " --agents 20 --steps 30 --queue-capacity 1 --queue-leavers-first");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--queue-leavers-first: needs --queue-clear-after > 0"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// --battery-* / --chargers (tasks/battery.hpp, the SUMO controller's fleet.battery on the
// grid): 20 agents with half a charge and a drain that empties it in 200 moves (300 steps);
// the critical charge covers 100 moves, more than the way to a charger (with 0.5 Wh per
// move and critical 0.1, 10 of 20 ran empty: the chargers were farther); chargers on
// the start cells of agents 20..27 (free cells nobody starts on). Charging keeps every
// agent above empty; drain only (--battery-no-charging) lets agents run empty.
TEST(LifelongCli, BatteryChargingKeepsEveryAgentAboveEmpty)
{
  const std::string dir = ttest::kData + "/2024/random.domain";
  std::ifstream agents(dir + "/agents/random_32_32_20_100.agents");
  std::string line;
  std::vector<std::string> cells;
  while (std::getline(agents, line))
    if (!line.empty() && line[0] != '#') cells.push_back(line);
  ASSERT_GE(cells.size(), 29u);  // the count, then the cells
  std::string chargers = "8\n";
  for (int i = 21; i < 29; ++i) chargers += cells[i] + "\n";
  const std::string file = test::temp_file("chargers.txt", chargers);
  const std::string base = "--problem " + dir + "/RANDOM-01.json --agents 20 --steps 300 --budget-ms 1000 "
                           "--budget-expansions 20 --seed 1 --quiet --chargers " + file +
                           " --battery-capacity-wh 100 --battery-initial 0.5 --battery-per-m-wh 0.25 --battery-threshold 0.4 "
                           "--battery-critical 0.25 --battery-target 0.9 --battery-charge-w 36000";
  for (bool charging : {true, false}) {
    SCOPED_TRACE(charging ? "charging" : "drain only");
    const CliRun r = run_cli(base + (charging ? "" : " --battery-no-charging"));
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.contains("battery")) << r.out;
    const auto& b = j["battery"];
    EXPECT_EQ(b["charging"], charging);
    EXPECT_GT(j["numTaskFinished"].get<int>(), 0);
    if (charging) {
      EXPECT_EQ(b["ran_empty"], 0);
      EXPECT_GT(b["min_charge"].get<double>(), 0.0);
      EXPECT_GE(b["charging_errands"].get<int>(), 10);
      EXPECT_GT(b["min_charge"].get<double>(), 0.1);
      EXPECT_GT(b["charging_share"].get<double>(), 0.0);
    } else {
      EXPECT_GT(b["ran_empty"].get<int>(), 0);
      EXPECT_EQ(b["min_charge"].get<double>(), 0.0);
      EXPECT_EQ(b["charging_errands"], 0);
    }
  }
  // Without any battery option: no battery in the log.
  const CliRun plain = run_cli("--problem " + dir + "/RANDOM-01.json --agents 20 --steps 5 --budget-expansions 20 --quiet");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("battery"));
}

TEST(LifelongCli, BadBatteryOptionsAreOneLineErrors)
{
  const std::string p = "--problem " + ttest::kData + "/2024/random.domain/RANDOM-01.json --agents 5 --steps 5 --quiet ";
  CliRun r = run_cli(p + "--battery-threshold 0.9 --battery-target 0.5 --battery-no-charging");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "rtlacam-lifelong: --battery-threshold: must be < target (0.5), got 0.9\n");
  r = run_cli(p + "--battery-initial 0.5");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "rtlacam-lifelong: --chargers: charging is on, but no charger cell is given\n");
  r = run_cli(p + "--battery-critical 0.4 --battery-no-charging");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "rtlacam-lifelong: --battery-critical: must be >= 0 and < threshold (0.3), got 0.4\n");
}

// The log carries the task layer's counts, named as in the SUMO controller's metrics.json
// "lifelong" (tasks::LifelongEpochs::count): the longest an agent kept one goal, the most
// busy agents heading for one errand cell, agent-steps on a queue cell, idle and parked
// agents at the end. 20 agents, 5 tasks revealed at once (--pool-size): most are idle, and
// with --parking (8 cells) they wait there; one agent per station with --queue-capacity 1.
TEST(LifelongCli, LogHasTheControllersLifelongCounts)
{
  const std::string dir = ttest::kData + "/2024/random.domain";
  std::ifstream agents(dir + "/agents/random_32_32_20_100.agents");
  std::string line;
  std::vector<std::string> cells;
  while (std::getline(agents, line))
    if (!line.empty() && line[0] != '#') cells.push_back(line);
  ASSERT_GE(cells.size(), 29u);
  std::string parking = "8\n";
  for (int i = 21; i < 29; ++i) parking += cells[i] + "\n";
  const std::string file = test::temp_file("parking.txt", parking);
  const std::string base = "--problem " + dir + "/RANDOM-01.json --agents 20 --steps 150 --budget-ms 1000 "
                           "--budget-expansions 20 --seed 1 --quiet --mode pool --pool-size 5 ";
  CliRun r = run_cli(base + "--parking " + file + " --queue-capacity 1 --queue-length 2");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("maxErrandTicks")) << r.out;
  EXPECT_GT(j["maxErrandTicks"].get<long long>(), 10);
  EXPECT_EQ(j["queues"]["maxHeading"], 1);  // --queue-capacity 1
  EXPECT_GE(j["parking"]["idleAtEnd"].get<int>(), 15);  // 20 agents, 5 tasks
  EXPECT_GE(j["parking"]["parkedAtEnd"].get<int>(), 4);
  EXPECT_LE(j["parking"]["parkedAtEnd"].get<int>(), 8);
  EXPECT_TRUE(j.contains("stallTicks"));
  EXPECT_GT(j["numErrandFinished"].get<int>(), 5);
  // Without parking and queues: nobody parked, and the crowd at a station is not capped.
  r = run_cli(base);
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["parking"]["parkedAtEnd"], 0);
  EXPECT_EQ(j["queues"]["queuedTicks"], 0);
  EXPECT_GE(j["parking"]["idleAtEnd"].get<int>(), 15);
}

// --highways reaches the lifelong LaCAM planners (it was bench/Python/SUMO only): on a map
// with 1-wide aisles (warehouse-10-20-10-2-1) the executed paths change and stay valid
// (the run validates every step: numPlannerErrors 0); the problem file names its map, agents
// and tasks by absolute paths, which the reader takes as they are; a planner without PIBT ranking by
// distances refuses it with one line and exit 2.
TEST(LifelongCli, HighwaysReachTheLifelongPlanner)
{
  const std::string map = std::string(RTLACAM_TEST_DATA) + "/planner/warehouse-10-20-10-2-1.map";
  const planner::Graph g = planner::load_map(map);
  // 60 agents on the first 60 free cells of every 90th, tasks on every 37th free cell.
  std::string agents = "60\n", tasks;
  int n_tasks = 0;
  std::vector<int> cells;
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x)
      if (g.at(x, y) >= 0) cells.push_back(y * g.width() + x);
  for (int i = 0; i < 60; ++i) agents += std::to_string(cells[(i * 90) % cells.size()]) + "\n";
  for (size_t i = 5; i < cells.size(); i += 37, ++n_tasks) tasks += std::to_string(cells[i]) + "\n";
  const std::string af = test::temp_file("hw.agents", agents), tf = test::temp_file("hw.tasks", std::to_string(n_tasks) + "\n" + tasks);
  const std::string problem = test::temp_file(
      "hw.json", "{\"mapFile\": \"" + map + "\", \"agentFile\": \"" + af + "\", \"taskFile\": \"" + tf +
                     "\", \"teamSize\": 60, \"numTasksReveal\": 1, \"taskAssignmentStrategy\": \"roundrobin\"}");
  const std::string base = "--problem " + problem + " --steps 120 --budget-ms 1000 --budget-expansions 30 --seed 2 ";
  const std::string off = test::temp_path("hw0.json"), on = test::temp_path("hw1.json");
  CliRun r = run_cli(base + "--solver rtlacam --quiet --out " + off);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_cli(base + "--solver rtlacam --quiet --highways 1 --out " + on);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream a(off), b(on);
  const auto j0 = nlohmann::json::parse(a), j1 = nlohmann::json::parse(b);
  EXPECT_FALSE(j0.contains("highways"));
  EXPECT_EQ(j1["highways"], 1);
  EXPECT_EQ(j0["numPlannerErrors"], 0);
  EXPECT_EQ(j1["numPlannerErrors"], 0);
  EXPECT_GT(j1["numErrandFinished"].get<int>(), 0);
  EXPECT_NE(j0["actualPaths"], j1["actualPaths"]);
  r = run_cli(base + "--quiet --solver pibt --highways 1");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--highways needs"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// Bad values are one line naming the option or file, exit 2: --pool-size 2^31 - 1 ran out of
// memory (rc 1), a directory as the problem or simulation_time.json threw "basic_filebuf::
// underflow" naming no file (rc 1), a directory as --guidance read as an empty guidance file
// (rc 0), and --steps -5 or a bad simulation_time.json value said "no simulation_time.json
// entry for this problem: pass --steps".
TEST(LifelongCli, BadValuesAndDirectoriesNameTheirOptionOrFile)
{
  const std::string dir = test::temp_dir("bad_values");
  auto put = [&](const std::string& name, const std::string& text) { std::ofstream(dir + "/" + name) << text; };
  put("p.map", "type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n");
  put("p.agents", "2\n0\n3\n");
  put("p.tasks", "3\n11\n8\n2,9\n");
  put("P-01.json", R"({"mapFile":"p.map","agentFile":"p.agents","teamSize":2,"taskFile":"p.tasks","version":"2024"})");
  const std::string problem = dir + "/P-01.json", quiet = " --budget-ms 1 --quiet";
  auto expect_bad = [](const CliRun& r, const std::string& what) {
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.out, "");
  };
  expect_bad(run_cli("--problem " + problem + " --steps 5 --pool-size 2147483647" + quiet), "--pool-size");
  expect_bad(run_cli("--problem " + dir + " --steps 5" + quiet), dir + ": is a directory, not a file");
  expect_bad(run_cli("--problem " + problem + " --steps -5" + quiet), "--steps: must be a number >= 0, not '-5'");
  expect_bad(run_cli("--problem " + problem + " --steps 5 --agents 0" + quiet), "--agents: must be a positive number, not '0'");
  expect_bad(run_cli("--problem " + problem + " --steps 5 --solver epibt --guidance " + dir + quiet),
             dir + ": is a directory, not a file");
  std::filesystem::create_directory(dir + "/simulation_time.json");
  expect_bad(run_cli("--problem " + problem + quiet), dir + "/simulation_time.json: is a directory, not a file");
  std::filesystem::remove(dir + "/simulation_time.json");
  for (const std::string value : {"-5", "0", "\"600\"", "1.5"}) {
    put("simulation_time.json", "{\"P-01\": " + value + "}");
    expect_bad(run_cli("--problem " + problem + quiet), dir + "/simulation_time.json: 'P-01': steps must be an integer");
  }
  put("simulation_time.json", "{\"01\": 7}");  // the longest key ending the name; --steps wins
  CliRun r = run_cli("--problem " + problem + quiet);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["makespan"], 7);
  r = run_cli("--problem " + problem + " --steps 3" + quiet);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["makespan"], 3);
}

// A run that cannot progress warns in one line and says so in the log: errands in another
// component than their agent (a wall splits the row), or two agents that must swap in a
// corridor (the planner proves the epoch unsolvable). Both ran silently to rc 0 with 0 tasks.
TEST(LifelongCli, RunsThatCannotProgressWarn)
{
  const std::string dir = test::temp_dir("stuck");
  auto put = [&](const std::string& name, const std::string& text) { std::ofstream(dir + "/" + name) << text; };
  put("split.map", "type octile\nheight 1\nwidth 5\nmap\n..@..\n");
  put("corr.map", "type octile\nheight 1\nwidth 5\nmap\n.....\n");
  put("a.agents", "2\n0\n4\n");
  put("split.tasks", "2\n3\n1\n");
  put("corr.tasks", "2\n4\n0\n");
  for (const std::string name : {"split", "corr"})
    put(name + ".json", "{\"mapFile\":\"" + name + ".map\",\"agentFile\":\"a.agents\",\"teamSize\":2,\"taskFile\":\"" + name +
                            ".tasks\",\"numTasksReveal\":1,\"taskAssignmentStrategy\":\"roundrobin\"}");
  CliRun r = run_cli("--problem " + dir + "/split.json --steps 20 --budget-ms 1 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["numTaskFinished"], 0);
  EXPECT_EQ(j["unreachableGoals"], 2);
  EXPECT_EQ(r.err.rfind("rtlacam-lifelong: warning: 2 agent(s) at the end cannot reach their goal", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = run_cli("--problem " + dir + "/corr.json --steps 50 --budget-ms 1 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["unreachableGoals"], 0);
  EXPECT_EQ(j["unsolvableEpoch"], true);
  EXPECT_NE(r.err.find("warning: the planner proved the last epoch's goals unsolvable"), std::string::npos) << r.err;
  // A run that progresses: no warning.
  r = run_cli("--problem " + ttest::kData + "/2024/random.domain/RANDOM-01.json --agents 10 --steps 20 --budget-ms 1 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["unreachableGoals"], 0);
  EXPECT_EQ(j["unsolvableEpoch"], false);
}
