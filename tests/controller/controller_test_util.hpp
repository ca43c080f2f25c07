#pragma once
// Helpers shared by the controller tests: the first config error of a YAML text, a whole
// file as a string, and "SUMO itself recorded no collision" for a run's output dir.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "controller/config.hpp"

namespace ctest_util {

inline std::string slurp(const std::string& path)
{
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The message of the ConfigError the YAML raises ("(no error)" when it parses).
inline std::string config_error(const std::string& yaml)
{
  try {
    controller::parse_config(yaml, "t.yaml", RTLACAM_CONFIGS);
  } catch (const controller::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

inline void expect_no_sumo_collision(const std::string& out_dir)
{
  EXPECT_EQ(slurp(out_dir + "/collision.xml").find("<collision "), std::string::npos) << out_dir;
}

}  // namespace ctest_util
