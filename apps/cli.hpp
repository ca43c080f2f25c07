#pragma once
// Conventions every rtlacam app shares (README "Exit codes"):
//   --version prints "<app> <version>" and exits 0;
//   exit codes: 0 ok, 1 runtime error (SUMO failed, an AGV vanished, a file could not be
//   written), 2 bad input (command line, files, config, net), 3 invalid plan or unsafe
//   execution (a validator conflict or jump, AGVs overlapping, a SUMO collision),
//   4 unsolved (a limit reached first; an instance proven unsolvable), 128 + N stopped by
//   signal N (130 SIGINT, 143 SIGTERM) with every output written.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

namespace cli {

enum Exit : int { kOk = 0, kRuntimeError = 1, kBadInput = 2, kInvalidPlan = 3, kUnsolved = 4 };

// SIGINT -> 130, SIGTERM -> 143 (the shell's convention for a process a signal ended).
inline int signal_exit(int sig) { return 128 + sig; }

// A number in [lo, hi]: CLI::Range lets NaN through (every comparison with it is false),
// and a negative or infinite budget or limit would run unbounded.
inline CLI::Validator finite_range(double lo, double hi)
{
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        double v = 0;
        try {
          size_t used = 0;
          v = std::stod(s, &used);
          if (used != s.size()) return "'" + s + "' is not a number";
        } catch (const std::exception&) {
          return "'" + s + "' is not a number";
        }
        if (!(v >= lo && v <= hi)) return "'" + s + "' is out of range [" + CLI::detail::to_string(lo) + ", " +
                                          CLI::detail::to_string(hi) + "]";
        return "";
      },
      "NUMBER in [" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]");
}

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
