#include "tasks/solver.hpp"

#include <stdexcept>

#include "planner/naive_rt_lacam.hpp"
#include "planner/pibt_planner.hpp"
#include "planner/rt_lacam.hpp"

namespace tasks {

std::unique_ptr<planner::RealtimePlanner> make_planner(const std::string& solver, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::GoalTest test, uint64_t seed)
{
  planner::LacamOptions opt;
  opt.seed = seed;
  if (solver == "rtlacam") return std::make_unique<planner::RtLacam>(g, starts, goals, opt, nullptr, std::move(test));
  if (solver == "naive") return std::make_unique<planner::NaiveRtLacam>(g, starts, goals, opt, nullptr, std::move(test));
  if (solver == "pibt") return std::make_unique<planner::PibtPlanner>(g, starts, goals, opt, nullptr, std::move(test));
  throw std::invalid_argument("unknown solver '" + solver + "' (pibt | naive | rtlacam)");
}

}  // namespace tasks
