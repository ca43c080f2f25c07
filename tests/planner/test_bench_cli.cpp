// rtlacam-bench end to end: runs, JSON output, plan file, and bad input -> one clear
// line on stderr and a non-zero exit code.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <vector>

#include "cli_run.hpp"
#include <cstdio>
#include <fstream>
#include <sstream>

namespace {

using Result = test::CliResult;
Result run(const std::string& args) { return test::run_cli(RTLACAM_BENCH_BIN, args); }

const std::string kDir = RTLACAM_TEST_DATA "/planner/";
const std::string kMap = kDir + "random-32-32-20.map";
const std::string kScen = kDir + "random-32-32-20-random-1.scen";

std::string tmp(const std::string& name, const std::string& text) { return test::temp_file(name, text); }

}  // namespace

TEST(BenchCli, RunsEverySolverAndPrintsJson)
{
  for (std::string solver : {"pibt", "lacam", "rtlacam", "naive"}) {
    Result r = run("--map " + kMap + " --scen " + kScen + " -N 50 --solver " + solver + " --json --cutoff-ms 1");
    EXPECT_EQ(r.code, 0) << solver << ": " << r.err;
    for (std::string key : std::vector<std::string>{"\"solved\":true", "\"total_planning_ms\"", "\"norm_soc\"", "\"soc_lb\"", "\"p99_iteration_ms\"",
                            "\"valid\":true", "\"solver\":\"" + solver + "\""})
      EXPECT_NE(r.out.find(key), std::string::npos) << key << " missing in " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "one JSON line";
  }
}

TEST(BenchCli, WritesThePlanInLacamFormat)
{
  std::string out = test::temp_path("plan.txt");
  Result r = run("--map " + kMap + " --scen " + kScen + " -N 20 --solver rtlacam --budget-expansions 1 --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(out);
  std::string line, all;
  int steps = 0;
  bool in_solution = false;
  while (std::getline(f, line)) {
    all += line + "\n";
    if (in_solution) ++steps;
    if (line == "solution=") in_solution = true;
  }
  for (std::string key : std::vector<std::string>{"agents=20\n", "solved=1\n", "soc=", "soc_lb=", "makespan=", "comp_time=", "starts=(", "goals=("})
    EXPECT_NE(all.find(key), std::string::npos) << key;
  EXPECT_NE(all.find("\n0:("), std::string::npos);
  EXPECT_GT(steps, 1);
}

TEST(BenchCli, BadInputGivesOneLineAndNonZeroExit)
{
  struct Case {
    std::string args, expect;
  };
  std::string bad_map = tmp("bad.map", "type octile\nheight 2\nwidth 2\nmap\n..\n.\n");
  std::string dup = tmp("dup.scen", "version 1\n0\tm\t32\t32\t0\t0\t5\t0\t5\n0\tm\t32\t32\t0\t0\t6\t0\t6\n");
  std::vector<Case> cases = {
      {"--map /nope.map --scen " + kScen + " -N 5", "/nope.map: cannot open"},
      {"--map " + bad_map + " --scen " + kScen + " -N 5", "bad.map:6"},
      {"--map " + kMap + " --scen " + kScen + " -N 100000", "only 409"},
      {"--map " + kMap + " --scen " + dup + " -N 2", "dup.scen:3: agent 1: duplicate start"},
      {"--map " + kMap + " --scen " + kScen + " -N 5 --solver magic", "solver"},
  };
  for (auto& c : cases) {
    Result r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << "stderr: " << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
}

// Option values out of range are bad input (2) with one readable line naming the option:
// they ran silently (a negative step limit, NaN rates and budgets, a negative margin), ran
// out of memory (rc 1: --lns-window 2^30), or printed DBL_MAX in 309 digits (-N 0).
TEST(BenchCli, OptionValuesOutOfRangeAreBadInput)
{
  struct Case {
    std::string args, expect;
  };
  const std::string base = "--map " + kMap + " --scen " + kScen + " -N 5 --json ";
  const std::vector<Case> cases = {
      {"--map " + kMap + " --scen " + kScen + " -N 0", "--agents: must be a positive number, not '0'"},
      {base + "--max-steps -1", "--max-steps: must be a number >= 0, not '-1'"},
      {base + "--restart-rate -1", "--restart-rate: '-1' is out of range"},
      {base + "--restart-rate 2", "--restart-rate: '2' is out of range"},
      {base + "--restart-rate nan", "--restart-rate: 'nan' is out of range"},
      {base + "--pause-min-ms nan", "--pause-min-ms: must be a number >= 0, not 'nan'"},
      {base + "--lg-budget nan", "--lg-budget: 'nan' is out of range"},
      {base + "--scatter-margin -5", "--scatter-margin"},
      {base + "--lns-window 1073741824", "--lns-window"},
      {base + "--lns-window 1000000", "--lns-window 1000000: the LNS table of (window + 1) x 819 vertices exceeds 2^28 cells"},
      {base + "--one-way-aisles", "--one-way-aisles: '" + kMap + "' with one-way aisles is not strongly connected"},
  };
  for (const Case& c : cases) {
    const Result r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_LT(r.err.size(), 200u) << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
}

TEST(BenchCli, UnsolvedExitsFourAndStillPrintsTheResult)
{
  // Two steps cannot bring 50 agents to their goals: the step limit comes first.
  Result r = run("--map " + kMap + " --scen " + kScen + " -N 50 --solver pibt --max-steps 2 --json");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.out.find("\"solved\":false"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"step_limit\":true"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"valid\":true"), std::string::npos) << r.out;
}

TEST(BenchCli, ProgressLinesGoToStderrOnlyForLongRuns)
{
  // A short run under the default --progress-s 2: silent on stderr.
  Result quiet = run("--map " + kMap + " --scen " + kScen + " -N 20 --solver rtlacam --json");
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  // Progress every 0.1 ms: lines for the iterations (rtlacam) and for slices of the one
  // full-horizon search (lacam); stdout stays one JSON line with the same result.
  for (std::string solver : {"rtlacam", "lacam"}) {
    Result r = run("--map " + kMap + " --scen " + kScen + " -N 150 --solver " + solver +
                   " --json --budget-expansions 1 --cutoff-ms 1000 --progress-s 0.0001");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.rfind("[rtlacam-bench] " + solver + " N=150: ", 0), 0u) << r.err;
    EXPECT_GE(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_NE(r.out.find("\"solved\":true"), std::string::npos) << r.out;
  }
}

// --budget-expansions alone is the whole budget of an iteration (deterministic runs): the
// default 1 ms wall cutoff does not cut it too. Checked with the earlier behaviour (the wall
// cutoff kept): "cutoff_ms" 1, and two runs made 130 and 61 expansions (here: 210 both).
TEST(BenchCli, AnExpansionsBudgetAloneHasNoWallCutoff)
{
  const std::string base = "--map " + kMap + " --scen " + kScen + " -N 100 --solver rtlacam --json --max-steps 3 ";
  const auto expansions = [](const std::string& out) {
    const auto at = out.find("\"expansions\":");
    return at == std::string::npos ? -1L : std::stol(out.substr(at + 13));
  };
  Result a = run(base + "--budget-expansions 3000"), b = run(base + "--budget-expansions 3000");
  ASSERT_TRUE(a.code == 0 || a.code == 4) << a.err;  // 4: not at the goals after 3 steps
  EXPECT_NE(a.out.find("\"cutoff_ms\":null"), std::string::npos) << a.out;
  EXPECT_GT(expansions(a.out), 0) << a.out;
  EXPECT_EQ(expansions(a.out), expansions(b.out)) << "two runs of the same expansions budget differ";
  Result both = run(base + "--budget-expansions 3000 --cutoff-ms 1");  // both given: whichever ends first
  EXPECT_NE(both.out.find("\"cutoff_ms\":1"), std::string::npos) << both.out;
}
