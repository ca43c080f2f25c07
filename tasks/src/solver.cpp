#include "tasks/solver.hpp"

#include <stdexcept>

#include "planner/naive_rt_lacam.hpp"
#include "planner/pibt_planner.hpp"
#include "planner/rt_lacam.hpp"

namespace tasks {

std::unique_ptr<planner::RealtimePlanner> make_planner(const std::string& solver, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::GoalTest test, uint64_t seed,
                                                       planner::ActionPreference* pref, bool keep_priorities, bool refine)
{
  planner::LacamOptions opt;
  opt.seed = seed;
  opt.keep_priorities = keep_priorities;
  opt.refine = refine;
  std::unique_ptr<planner::RealtimePlanner> p;
  if (solver == "cspibt" && !pref) throw std::invalid_argument("solver cspibt needs a policy");
  if (solver == "rtlacam") p = std::make_unique<planner::RtLacam>(g, starts, goals, opt, pref, std::move(test));
  else if (solver == "naive") p = std::make_unique<planner::NaiveRtLacam>(g, starts, goals, opt, pref, std::move(test));
  else if (solver == "pibt" || solver == "cspibt")
    p = std::make_unique<planner::PibtPlanner>(g, starts, goals, opt, pref, std::move(test));
  else throw std::invalid_argument("unknown solver '" + solver + "' (pibt | naive | rtlacam | cspibt)");
  // A lifelong run visits thousands of goal cells: keep the tables in use plus a few
  // hundred recent ones, not one per cell ever visited.
  p->set_max_dist_tables(2 * starts.size() + 256);
  return p;
}

}  // namespace tasks
