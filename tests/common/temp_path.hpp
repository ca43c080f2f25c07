#pragma once
// Scratch paths for tests. ctest runs every TEST in its own process and several at once
// (-j2), so a fixed name under /tmp is shared by concurrent tests: one test reads what
// another wrote. Every path here carries the process id. They are removed when the process
// ends with every test passed (kept for a look after a failure, or with RTLACAM_KEEP_TEST_FILES).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace test {

// The paths handed out, removed at exit (above). Constructed after gtest's UnitTest, so
// destroyed before it: Failed() is still there to ask.
struct TempPaths {
  std::vector<std::string> paths;
  ~TempPaths()
  {
    if (std::getenv("RTLACAM_KEEP_TEST_FILES") || testing::UnitTest::GetInstance()->Failed()) return;
    std::error_code ec;
    for (const std::string& p : paths) std::filesystem::remove_all(p, ec);
  }
};

inline TempPaths& temp_paths()
{
  static TempPaths t;
  return t;
}

// A file path private to this test process.
inline std::string temp_path(const std::string& name)
{
  std::string dir = testing::TempDir();
  if (!dir.empty() && dir.back() != '/') dir += '/';
  std::string p = dir + "rtlacam_" + std::to_string(::getpid()) + "_" + name;
  temp_paths().paths.push_back(p);
  return p;
}

// That path, written with `text`.
inline std::string temp_file(const std::string& name, const std::string& text)
{
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

// A fresh, empty directory private to this test process.
inline std::string temp_dir(const std::string& name)
{
  const std::filesystem::path d = temp_path(name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

}  // namespace test
