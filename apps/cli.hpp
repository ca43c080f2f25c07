#pragma once
// Conventions every rtlacam app shares (README "Exit codes"):
//   --version prints "<app> <version>" and exits 0;
//   exit codes: 0 ok, 1 runtime error, 2 bad input (command line, files, config),
//   3 invalid plan (a validator violation), 4 unsolved / a limit reached first.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

namespace cli {

enum Exit : int { kOk = 0, kRuntimeError = 1, kBadInput = 2, kInvalidPlan = 3, kUnsolved = 4 };

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
