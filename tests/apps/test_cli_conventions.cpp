// Conventions every app shares (apps/cli.hpp, README "Exit codes"): --version prints
// "<app> <version>" and exits 0; a bad command line exits 2 with one line on stderr
// naming the app; --help exits 0.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "cli_run.hpp"

namespace {

struct App {
  std::string name, bin;
};

std::vector<App> apps()
{
  return {
#ifdef RTLACAM_BENCH_BIN
      {"rtlacam-bench", RTLACAM_BENCH_BIN},
#endif
#ifdef RTLACAM_GRIDIFY_BIN
      {"rtlacam-gridify", RTLACAM_GRIDIFY_BIN},
#endif
#ifdef RTLACAM_LIFELONG_BIN
      {"rtlacam-lifelong", RTLACAM_LIFELONG_BIN},
#endif
#ifdef RTLACAM_POLICY_BIN
      {"rtlacam-policy", RTLACAM_POLICY_BIN},
#endif
#ifdef RTLACAM_SUMO_BIN
      {"rtlacam-sumo", RTLACAM_SUMO_BIN},
#endif
  };
}

}  // namespace

TEST(CliConventions, EveryAppIsTested)
{
  // bench, gridify, lifelong and policy build without SUMO; rtlacam-sumo only with it.
  EXPECT_GE(apps().size(), 4u);
}

TEST(CliConventions, VersionPrintsNameAndVersionAndExitsZero)
{
  for (const App& a : apps()) {
    const test::CliResult r = test::run_cli(a.bin, "--version");
    EXPECT_EQ(r.code, 0) << a.name << ": " << r.err;
    EXPECT_EQ(r.out, a.name + " " RTLACAM_VERSION "\n") << a.name;
  }
}

TEST(CliConventions, HelpExitsZero)
{
  for (const App& a : apps()) {
    const test::CliResult r = test::run_cli(a.bin, "--help");
    EXPECT_EQ(r.code, 0) << a.name << ": " << r.err;
    EXPECT_NE(r.out.find(a.name), std::string::npos) << a.name << " usage: " << r.out;
  }
}

TEST(CliConventions, BadCommandLineIsBadInputWithOneLine)
{
  // No arguments (a required one missing) and an unknown option: exit 2, one line naming
  // the app (CLI11 alone exits 106 / 109 with two lines).
  for (const App& a : apps()) {
    for (const std::string args : {"", "--no-such-option"}) {
      const test::CliResult r = test::run_cli(a.bin, args);
      EXPECT_EQ(r.code, 2) << a.name << " " << args << ": " << r.err;
      EXPECT_EQ(r.err.rfind(a.name + ": ", 0), 0u) << a.name << ": " << r.err;
      EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
      EXPECT_EQ(r.out, "") << a.name;
    }
  }
}

// A count that must be positive says so in words: CLI::PositiveNumber printed "Value 0 not in
// range 0.000000 to 1797693...(309 digits)" and let NaN through (apps/cli.hpp positive()).
TEST(CliConventions, PositiveCountsSayWhatIsWrongReadably)
{
  std::vector<std::pair<std::string, std::string>> runs;  // binary, arguments
#ifdef RTLACAM_BENCH_BIN
  runs.push_back({RTLACAM_BENCH_BIN, "--map m --scen s -N 0"});
#endif
#ifdef RTLACAM_LIFELONG_BIN
  runs.push_back({RTLACAM_LIFELONG_BIN, "--problem p --agents 0"});
#endif
#ifdef RTLACAM_POLICY_BIN
  runs.push_back({RTLACAM_POLICY_BIN, "time --weights w --map m --scen s -N 0"});
#endif
#ifdef RTLACAM_SUMO_BIN
  runs.push_back({RTLACAM_SUMO_BIN, "c.yaml --max-ticks 0"});
#endif
  for (const auto& [bin, args] : runs) {
    const test::CliResult r = test::run_cli(bin, args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find("must be a positive number, not '0'"), std::string::npos) << args << ": " << r.err;
    EXPECT_LT(r.err.size(), 160u) << r.err;
    const test::CliResult nan = test::run_cli(bin, args.substr(0, args.size() - 1) + "nan");
    EXPECT_EQ(nan.code, 2) << args << ": " << nan.err;
  }
}
