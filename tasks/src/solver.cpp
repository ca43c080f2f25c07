#include "tasks/solver.hpp"

#include <stdexcept>

#include "planner/rotation/epibt.hpp"
#include "planner/rotation/rotation_pibt.hpp"
#include "planner/rotation/wppl.hpp"
#include "planner/solver.hpp"

namespace tasks {

std::unique_ptr<planner::RealtimePlanner> make_planner(const std::string& solver, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::GoalTest test, uint64_t seed,
                                                       planner::ActionPreference* pref, bool keep_priorities, bool refine)
{
  if (solver == kEpibtSolver) {
    auto p = std::make_unique<planner::Epibt>(g, starts, goals, planner::Epibt::Options{}, std::move(test));
    p->set_max_dist_tables(starts.size() + 256);  // as pibt-rot's
    return p;
  }
  if (solver == kWpplSolver) {
    auto p = std::make_unique<planner::Wppl>(g, starts, goals, seed, std::move(test));
    p->set_max_dist_tables(starts.size() + 256);  // as pibt-rot's
    return p;
  }
  if (is_rotation_native(solver)) {
    auto p = std::make_unique<planner::RotationPibt>(g, starts, goals, seed, std::move(test));
    // (cell, heading) tables are 2x a cell table: keep the goals in use + a few hundred.
    p->set_max_dist_tables(starts.size() + 256);
    return p;
  }
  planner::LacamOptions opt;
  opt.seed = seed;
  opt.keep_priorities = keep_priorities;
  opt.refine = refine;
  auto p = planner::make_planner(planner::parse_solver(solver), g, starts, goals, opt, pref, std::move(test));
  // A lifelong run visits thousands of goal cells: keep the tables in use plus a few
  // hundred recent ones, not one per cell ever visited.
  p->set_max_dist_tables(2 * starts.size() + 256);
  return p;
}

}  // namespace tasks
