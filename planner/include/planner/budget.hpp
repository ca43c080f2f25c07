#pragma once
// Budget: how much search one planning call may do. Both limits apply; whichever runs out
// first ends the call. The expansion limit makes runs deterministic (tests); the
// wall-clock limit is the real-time cutoff.
#include <time.h>

#include <chrono>
#include <cstdint>
#include <limits>

namespace planner {

using Clock = std::chrono::steady_clock;

struct Budget {
  double ms = std::numeric_limits<double>::infinity();
  uint64_t expansions = std::numeric_limits<uint64_t>::max();
  // What one expansion may cost (ms): a search starts one only while it would end by the
  // deadline (an expansion cannot stop halfway), counting at least the costliest one of the
  // call so far. 0: it starts one until the deadline, as the paper's loop.
  double reserve_ms = 0;

  static Budget time_ms(double ms) { return {ms, std::numeric_limits<uint64_t>::max(), 0}; }
  static Budget expansion_count(uint64_t e) { return {std::numeric_limits<double>::infinity(), e, 0}; }
  static Budget unlimited() { return {}; }

  // Deadline for a call starting now (time_point::max() when unlimited).
  Clock::time_point deadline_from(Clock::time_point start) const
  {
    if (!(ms < 1e12)) return Clock::time_point::max();
    return start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(ms));
  }
};

// CPU time of the calling thread (ms): work, told apart from time the thread was preempted.
inline double thread_cpu_ms()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

inline double ms_since(Clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace planner
