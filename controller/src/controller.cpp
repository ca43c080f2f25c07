#include "controller/controller.hpp"

#include "run.hpp"

#include "planner/naive_rt_lacam.hpp"
#include "planner/pibt_planner.hpp"
#include "planner/rt_lacam.hpp"

namespace controller {


std::unique_ptr<planner::RealtimePlanner> make_planner(const PlannerSection& p, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::ActionPreference* pref, planner::GoalTest test)
{
  planner::LacamOptions opt;
  opt.swap = p.swap;
  opt.seed = p.seed;
  opt.keep_priorities = p.keep_priorities;
  if (p.solver == "naive") return std::make_unique<planner::NaiveRtLacam>(g, starts, goals, opt, pref, std::move(test));
  if (p.solver == "pibt" || p.solver == "cspibt") {
    if (p.solver == "cspibt" && !pref) throw std::invalid_argument("solver cspibt needs a policy (planner.policy)");
    return std::make_unique<planner::PibtPlanner>(g, starts, goals, opt, pref, std::move(test));
  }
  return std::make_unique<planner::RtLacam>(g, starts, goals, opt, pref, std::move(test));
}

std::unique_ptr<SumoBackend> make_backend(const RunSection& r)
{
  if (r.gui) return make_traci_backend("sumo-gui", r.port);
  if (r.backend == "traci") return make_traci_backend("sumo", r.port);
  return make_libsumo_backend();
}

Metrics Controller::run() { return Run(cfg_, *this).execute(); }

}  // namespace controller
