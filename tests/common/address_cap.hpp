#pragma once
// For tests of "a huge claimed size is an error, not an allocation". Linux overcommit
// grants a large allocation without touching it, so the code under test runs in a
// death-test child (EXPECT_EXIT) whose address space is capped: an allocation made before
// the size check throws std::bad_alloc there, as on hosts without overcommit or under
// `ulimit -v`. AddressSanitizer reserves far more address space than any cap, so such
// tests skip under it.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>

#include "planner/error.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define RTLACAM_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RTLACAM_UNDER_ASAN 1
#endif
#endif
#ifndef RTLACAM_UNDER_ASAN
#define RTLACAM_UNDER_ASAN 0
#endif

#define RTLACAM_SKIP_UNDER_ASAN() \
  if (RTLACAM_UNDER_ASAN) GTEST_SKIP() << "AddressSanitizer reserves more address space than the cap"

namespace test {

// The address space this process uses now (bytes).
inline rlim_t address_space_now()
{
  long pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  return static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE));
}

// In the death-test child: caps the address space at `bytes` and runs `load`. Exits 0 if it
// throws planner::InputError, 1 on any other exception, 2 if it returns; the message goes
// to stderr for EXPECT_EXIT's matcher.
template <class Load>
[[noreturn]] void exit_after_capped(rlim_t bytes, Load load)
{
  const rlimit cap{bytes, bytes};
  setrlimit(RLIMIT_AS, &cap);
  try {
    load();
  } catch (const planner::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    std::exit(0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    std::exit(1);
  }
  std::exit(2);
}

}  // namespace test
