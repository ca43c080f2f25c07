#pragma once
// Shared bits of the libFuzzer targets (see README.md): scratch files private to the
// fuzzer process, splitting one input into several files, and the rule for exceptions.
//
// Bad input must end in a one-line error: planner::InputError (or the controller's
// ConfigError) is the expected outcome. Anything else escaping a reader is a finding:
//  - a crash, hang, sanitizer report or out-of-memory: libFuzzer reports it itself;
//  - another exception: the apps print it without the file name (or, rtlacam-gridify,
//    not at all), so with RTLACAM_FUZZ_STRICT=1 in the environment it aborts too;
//  - an error message with a line break: the apps print "error: <what>" on one line.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <typeinfo>
#include <vector>

namespace fuzz {

// "/tmp/rtlacam_fuzz_<pid>_<name>": one fuzzer per process, so the pid keeps runs apart.
inline std::string temp_path(const std::string& name)
{
  return "/tmp/rtlacam_fuzz_" + std::to_string(::getpid()) + "_" + name;
}

inline std::string write_file(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

// The input cut at NUL bytes into at most `n` parts (text formats never contain NUL, so
// one input can carry a main file plus a companion file).
inline std::vector<std::string> split(const uint8_t* data, size_t size, size_t n)
{
  std::vector<std::string> parts(1);
  for (size_t k = 0; k < size; ++k) {
    if (data[k] == 0 && parts.size() < n) parts.emplace_back();
    else parts.back() += static_cast<char>(data[k]);
  }
  return parts;
}

[[noreturn]] inline void finding(const char* what, const std::exception& e)
{
  std::fprintf(stderr, "\nFUZZ FINDING: %s: %s: %s\n", what, typeid(e).name(), e.what());
  std::abort();
}

// Call for an expected error type: its message must be one line.
inline void expected(const std::exception& e)
{
  if (std::string(e.what()).find('\n') != std::string::npos) finding("multi-line error message", e);
}

// Call for any other std::exception.
inline void unexpected(const std::exception& e)
{
  static const bool strict = std::getenv("RTLACAM_FUZZ_STRICT") != nullptr;
  if (strict) finding("unexpected exception type", e);
}

}  // namespace fuzz
