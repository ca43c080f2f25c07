// The policy from the command line: rtlacam-bench --solver cspibt / --policy, and
// rtlacam-policy dump/time. Bad input -> one clear line on stderr, non-zero exit code.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "cli_run.hpp"
#include "policy/dump_file.hpp"

namespace {

using Result = test::CliResult;
Result run(const std::string& bin, const std::string& args) { return test::run_cli(bin, args); }

const std::string kMap = RTLACAM_TEST_DATA "/planner/random-32-32-20.map";
const std::string kScen = RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen";
const std::string kWeights = RTLACAM_POLICY_MODELS "/random-32-32-20.bin";
const std::string kInstance = "--map " + kMap + " --scen " + kScen;

}  // namespace

TEST(PolicyCli, BenchRunsEverySolverWithThePolicy)
{
  for (std::string solver : {"cspibt", "pibt", "rtlacam", "naive", "lacam"}) {
    SCOPED_TRACE(solver);
    const Result r = run(RTLACAM_BENCH_BIN, kInstance + " -N 30 --solver " + solver + " --policy " + kWeights +
                                                " --json --budget-expansions 5 --max-steps 300");
    // 4: unsolved within --max-steps (cspibt/pibt/naive may not reach every goal); still a result.
    const bool solved = r.out.find("\"solved\":true") != std::string::npos;
    EXPECT_EQ(r.code, solved ? 0 : 4) << r.err;
    EXPECT_NE(r.out.find("\"valid\":true"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"solver\":\"" + solver + "\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"policy\":\"" + kWeights + "\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"policy_inferences\":"), std::string::npos) << r.out;
    if (solver == "rtlacam" || solver == "lacam") {
      EXPECT_NE(r.out.find("\"solved\":true"), std::string::npos) << r.out;
    }
  }
}

TEST(PolicyCli, BenchWithoutPolicyKeepsItsJson)
{
  const Result r = run(RTLACAM_BENCH_BIN, kInstance + " -N 20 --solver rtlacam --json");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find("policy"), std::string::npos) << r.out;
}

TEST(PolicyCli, BenchBadPolicyInput)
{
  Result r = run(RTLACAM_BENCH_BIN, kInstance + " -N 5 --solver cspibt");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "rtlacam-bench: --solver cspibt needs --policy WEIGHTS\n");

  const std::string bad = test::temp_path("policy_cli_bad.bin");
  std::ofstream(bad) << "RTLPOLCY\x01";
  r = run(RTLACAM_BENCH_BIN, kInstance + " -N 5 --solver rtlacam --policy " + bad);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.rfind("rtlacam-bench: " + bad + ": truncated file: version", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;

  r = run(RTLACAM_BENCH_BIN, kInstance + " -N 5 --solver rtlacam --policy " + kMap);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("not a policy weights file (bad magic"), std::string::npos) << r.err;
}

TEST(PolicyCli, DumpWritesOneRecordPerAgentAndStep)
{
  const std::string out = test::temp_path("policy_cli_dump.bin");
  const Result r = run(RTLACAM_POLICY_BIN, "dump " + kInstance + " -N 10 20 --radius 2 --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  // Header: magic, version, radius, channels, features, 4 scales, count; then the records.
  std::ifstream in(out, std::ios::binary);
  char magic[8];
  uint32_t h[4];
  float scale[4];
  uint64_t count = 0;
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(h), sizeof h);
  in.read(reinterpret_cast<char*>(scale), sizeof scale);
  in.read(reinterpret_cast<char*>(&count), sizeof count);
  EXPECT_EQ(std::string(magic, 8), "RTLPDUMP");
  EXPECT_EQ(h[0], 1u);
  EXPECT_EQ(h[1], 2u);
  EXPECT_EQ(h[2], 4u);
  EXPECT_EQ(h[3], 4u * 25);
  EXPECT_EQ(scale[2], 4.0f);
  EXPECT_EQ(scale[0], 1.0f);
  // Every agent at every step of both solutions: 10 * T1 + 20 * T2 records.
  long long makespan_sum = 0;
  std::istringstream log(r.err);
  std::string line;
  int n = 0;
  while (std::getline(log, line)) {
    const auto k = line.find("\"makespan\":");
    ASSERT_NE(k, std::string::npos) << line;
    makespan_sum += (n++ == 0 ? 10 : 20) * std::stoll(line.substr(k + 11));
  }
  EXPECT_EQ(n, 2);
  EXPECT_EQ(static_cast<long long>(count), makespan_sum);
  in.seekg(0, std::ios::end);
  EXPECT_EQ(static_cast<uint64_t>(in.tellg()), 8 + 16 + 16 + 8 + count * (100 + 2));
  EXPECT_NE(r.out.find("\"samples\":" + std::to_string(count)), std::string::npos) << r.out;
}

TEST(PolicyCli, TimePrintsJson)
{
  const Result r = run(RTLACAM_POLICY_BIN, "time --weights " + kWeights + " " + kInstance + " -N 50 --reps 3");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"forward_ms\":"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"agents\":50"), std::string::npos) << r.out;
}

// An agent on a cell with no free neighbour stays put: its random move drew rng.below(0)
// (a segfault). The 1x1 map's one agent, and an agent walled into a corner.
TEST(PolicyCli, TimeKeepsAnAgentWithoutNeighboursInPlace)
{
  const std::string one_map = test::temp_file("one.map", "type octile\nheight 1\nwidth 1\nmap\n.\n");
  const std::string one_scen = test::temp_file("one.scen", "version 1\n0\tone.map\t1\t1\t0\t0\t0\t0\t0\n");
  Result r = run(RTLACAM_POLICY_BIN, "time --weights " + kWeights + " --map " + one_map + " --scen " + one_scen + " -N 1 --reps 2");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"agents\":1"), std::string::npos) << r.out;
  const std::string iso_map = test::temp_file("iso.map", "type octile\nheight 3\nwidth 3\nmap\n...\n@@@\n.@@\n");
  const std::string iso_scen = test::temp_file(
      "iso.scen", "version 1\n0\tiso.map\t3\t3\t0\t2\t0\t2\t0\n0\tiso.map\t3\t3\t0\t0\t2\t0\t2\n");
  r = run(RTLACAM_POLICY_BIN, "time --weights " + kWeights + " --map " + iso_map + " --scen " + iso_scen + " -N 2 --reps 2");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"agents\":2"), std::string::npos) << r.out;
}

// Out-of-range values are bad input naming the option: dump -N -3 was a std::length_error
// (rc 1), --timeout-s -1 / nan ran with no search at all.
TEST(PolicyCli, OptionValuesOutOfRangeAreBadInput)
{
  const std::string out = test::temp_path("dump.bin");
  for (const auto& [args, what] : std::vector<std::pair<std::string, std::string>>{
           {"-N -3", "--agents: must be a positive number, not '-3'"},
           {"-N 5 -N 0", "--agents: must be a positive number, not '0'"},
           {"-N 5 --timeout-s -1", "--timeout-s: '-1' is out of range"},
           {"-N 5 --timeout-s nan", "--timeout-s: 'nan' is out of range"},
           {"-N 5 --keep nan", "--keep: 'nan' is out of range"}}) {
    const Result r = run(RTLACAM_POLICY_BIN, "dump " + kInstance + " --out " + out + " " + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}
