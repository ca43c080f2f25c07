#pragma once
// Drives an RT-LaCAM* to its goals, 100 expansions per search, every move checked by `v`;
// before each of the first `wait_steps` searches it waits for the refiner threads to publish
// (or give up), so what they hand over does not depend on the machine's load. Returns the
// moves made; a failed check is a test failure and ends the drive (the caller's at_goal
// assertion then fails too).
#include <gtest/gtest.h>

#include "planner/budget.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/validator.hpp"

namespace test {

inline int drive_refined(planner::RtLacam& rt, planner::Validator& v, int max_steps, int wait_steps = 0)
{
  int steps = 0;
  for (; steps < max_steps && !rt.at_goal(); ++steps) {
    if (steps < wait_steps) rt.lacam().wait_refiners(2000);
    rt.step(planner::Budget::expansion_count(100));
    rt.commit();
    if (!v.step(rt.current())) {
      ADD_FAILURE() << "move " << steps << ": " << v.error();
      break;
    }
  }
  return steps;
}

}  // namespace test
