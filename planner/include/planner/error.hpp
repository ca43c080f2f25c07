#pragma once
// Errors the planner reports for bad input. The message is one line that names the
// file and line (or the object) at fault, so a CLI can print it as is and exit non-zero.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace planner {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "path:line: what" (line omitted when 0).
inline InputError input_error(const std::string& path, int line, const std::string& what)
{
  return InputError(path + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what);
}

// A directory opens as an ifstream on Linux and then reads as an empty file (or throws
// "basic_filebuf::underflow ... Is a directory", naming no file): readers call this first.
inline void check_not_directory(const std::string& path)
{
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw input_error(path, 0, "is a directory, not a file");
}

}  // namespace planner
