// Timing assertions on a shared box: a single iteration's CPU time can be inflated from
// outside the process (a hypervisor preempting the vCPU is charged to the running thread;
// a neighbour's cache traffic), which a test cannot control. An overrun caused by the
// planner (an indivisible step longer than the budget) repeats on every run; an outside
// one does not. So a timing check runs the measurement up to `tries` times and keeps the
// first run that meets it, printing each miss so a flaky box is visible in the log.
#pragma once

#include <cstdio>

namespace test {

// run() -> R; ok(const R&) -> bool. Returns the first result with ok(), else the last.
template <class Run, class Ok>
auto first_within(int tries, Run run, Ok ok)
{
  auto r = run();
  for (int i = 1; i < tries && !ok(r); ++i) {
    std::printf("timing check missed on try %d of %d; measuring again\n", i, tries);
    r = run();
  }
  return r;
}

}  // namespace test
