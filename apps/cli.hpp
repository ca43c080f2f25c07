#pragma once
// Conventions every rtlacam app shares (README "Exit codes"):
//   --version prints "<app> <version>" and exits 0;
//   exit codes: 0 ok, 1 runtime error (SUMO failed, an AGV vanished, a file could not be
//   written), 2 bad input (command line, files, config, net), 3 invalid plan or unsafe
//   execution (a validator conflict or jump, AGVs overlapping, a SUMO collision),
//   4 unsolved (a limit reached first; an instance proven unsolvable), 128 + N stopped by
//   signal N (130 SIGINT, 143 SIGTERM) with every output written.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <string>

namespace cli {

enum Exit : int { kOk = 0, kRuntimeError = 1, kBadInput = 2, kInvalidPlan = 3, kUnsolved = 4 };

// SIGINT -> 130, SIGTERM -> 143 (the shell's convention for a process a signal ended).
inline int signal_exit(int sig) { return 128 + sig; }

// `s` as a number into `v`: "" when it reads whole, else why not. A magnitude beyond double
// (1e400) reads as +-HUGE_VAL with `overflow_is_huge`, else as not a number.
inline std::string read_number(const std::string& s, double& v, bool overflow_is_huge)
{
  try {
    size_t used = 0;
    v = std::stod(s, &used);
    if (used != s.size()) return "'" + s + "' is not a number";
  } catch (const std::out_of_range&) {
    if (!overflow_is_huge) return "'" + s + "' is not a number";
    v = s.find('-') == std::string::npos ? HUGE_VAL : -HUGE_VAL;
  } catch (const std::exception&) {
    return "'" + s + "' is not a number";
  }
  return "";
}

// A number in [lo, hi]: CLI::Range lets NaN through (every comparison with it is false),
// and a negative or infinite budget or limit would run unbounded.
inline CLI::Validator finite_range(double lo, double hi)
{
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        double v = 0;
        if (std::string bad = read_number(s, v, false); !bad.empty()) return bad;
        if (!(v >= lo && v <= hi)) return "'" + s + "' is out of range [" + CLI::detail::to_string(lo) + ", " +
                                          CLI::detail::to_string(hi) + "]";
        return "";
      },
      "NUMBER in [" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]");
}

// A finite number > 0 (positive) or >= 0 (non_negative): CLI::PositiveNumber and
// NonNegativeNumber let NaN through and print their bound as DBL_MAX in 309 digits
// ("Value 0 not in range 0.000000 to 179769313486231570814527..."). An integer option
// still gets CLI11's own check that the value is an integer (and fits) after this one.
inline CLI::Validator at_least(bool strict)
{
  const std::string want = strict ? "a positive number" : "a number >= 0";
  return CLI::Validator(
      [strict, want](std::string& s) -> std::string {
        double v = 0;
        // 1e400: too large, not "not a number".
        if (std::string bad = read_number(s, v, true); !bad.empty()) return bad;
        if (!std::isfinite(v) || (strict ? v <= 0 : v < 0)) return "must be " + want + ", not '" + s + "'";
        return "";
      },
      strict ? "POSITIVE" : "NON-NEGATIVE");
}
inline CLI::Validator positive() { return at_least(true); }
inline CLI::Validator non_negative() { return at_least(false); }

// Names the app (usage line, error prefix) and adds --version.
inline void add_version(CLI::App& app, const std::string& name)
{
  app.name(name);
  app.set_version_flag("--version", name + " " RTLACAM_VERSION);
}

}  // namespace cli

// CLI11_PARSE with our exit codes: --help/--version exit 0; a bad command line exits 2
// (CLI11's own codes are 100+) with one line "<app>: <what is wrong> (--help: usage)".
#define RTLACAM_PARSE(app, argc, argv)                                                    \
  try {                                                                                   \
    (app).parse((argc), (argv));                                                          \
  } catch (const CLI::ParseError& e) {                                                    \
    if (e.get_exit_code() == 0) return (app).exit(e);                                     \
    std::cerr << (app).get_name() << ": " << e.what() << " (--help: usage)" << std::endl; \
    return cli::kBadInput;                                                                \
  }
