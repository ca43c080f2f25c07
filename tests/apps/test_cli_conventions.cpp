// Conventions every app shares (apps/cli.hpp, README "Exit codes"): --version prints
// "<app> <version>" and exits 0; a bad command line exits 2 with one line on stderr
// naming the app; --help exits 0.
#include <gtest/gtest.h>

#include <string>
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
