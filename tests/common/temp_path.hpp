#pragma once
// Scratch paths for tests. ctest runs every TEST in its own process and several at once
// (-j2), so a fixed name under /tmp is shared by concurrent tests: one test reads what
// another wrote. Every path here carries the process id.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace test {

// A file path private to this test process.
inline std::string temp_path(const std::string& name)
{
  std::string dir = testing::TempDir();
  if (!dir.empty() && dir.back() != '/') dir += '/';
  return dir + "rtlacam_" + std::to_string(::getpid()) + "_" + name;
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
