#pragma once
// Runs one of our command-line apps from a test: exit code, stdout and stderr, so CLI
// tests can assert "one clear line on stderr and a non-zero exit".
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "temp_path.hpp"

namespace test {

struct CliResult {
  int code = -1;
  std::string out, err;
};

inline CliResult run_cli(const std::string& bin, const std::string& args)
{
  const std::string err_file = temp_path("cli_stderr.txt");
  const std::string cmd = bin + " " + args + " 2>" + err_file;
  CliResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  while (fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  return r;
}

}  // namespace test
