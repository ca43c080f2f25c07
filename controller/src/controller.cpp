#include "controller/controller.hpp"

#include "run.hpp"

#include "controller/display.hpp"
#include "controller/sumo_error.hpp"
#include "planner/solver.hpp"

namespace controller {


std::unique_ptr<planner::RealtimePlanner> make_planner(const PlannerSection& p, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::ActionPreference* pref, planner::GoalTest test,
                                                       const std::vector<int>& headings,
                                                       std::shared_ptr<planner::DistCache> cache,
                                                       std::shared_ptr<const planner::Zones> zones)
{
  planner::SolverOptions opt;
  opt.lacam.zones = std::move(zones);  // the cell solvers' zone rule (rules.plan_zones)
  opt.dist_cache = std::move(cache);
  opt.seed = p.seed;
  opt.lacam.swap = p.swap;
  opt.lacam.keep_priorities = p.keep_priorities;
  opt.lacam.refine = p.refine;
  opt.lacam.dive = p.dive;
  opt.lacam.lns_stop_cost = p.stop_cost;
  opt.lacam.lns_count_moves = p.lns_moves;
  opt.lacam.free_first = p.free_first;
  opt.lacam.highways = p.highways;
  opt.pref = pref;
  const planner::Solver kind = planner::parse_solver(p.solver);
  if (planner::plans_rotation(kind)) {
    planner::apply(p.rotation, g, opt);  // planner/rotation_settings.hpp
    opt.headings = headings;
  }
  return planner::make_planner(kind, g, starts, goals, opt, std::move(test));
}

std::unique_ptr<SumoBackend> make_backend(const RunSection& r)
{
  if (r.gui && r.port == 0) {
    // sumo-gui without a display dies at once and TraCI would retry for seconds: say so now.
    const std::string why = display_problem();
    if (!why.empty()) throw SumoError("sumo-gui: " + why);
  }
  // A SUMO to join is reached over TraCI: an embedded one would ignore the port unseen.
  if (r.port > 0 && !r.gui && r.backend != "traci")
    throw ConfigError("run.port " + std::to_string(r.port) + ": joining a SUMO needs run.backend traci (--backend traci), not " +
                      r.backend);
  if (r.gui) return make_traci_backend("sumo-gui", r.port, r.order);
  if (r.backend == "traci") return make_traci_backend("sumo", r.port, r.order);
  return make_libsumo_backend();
}

Metrics Controller::run() { return Run(cfg_, *this).execute(); }

}  // namespace controller
