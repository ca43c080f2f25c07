// rtlacam-lifelong end to end: the JSON log's fields, the default mode per round, exit
// codes and one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
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
