#include "planner/solver.hpp"

#include <stdexcept>

#include "planner/lacam/naive_rt_lacam.hpp"
#include "planner/lacam/pibt_planner.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/rotation/rotation_pibt.hpp"

namespace planner {
namespace {

constexpr Solver kAll[] = {Solver::Pibt,   Solver::Lacam,   Solver::RtLacam, Solver::Naive,
                           Solver::CsPibt, Solver::PibtRot, Solver::Epibt,   Solver::Wppl};

// The rotation options, applied in the order the lifelong runner applied them before the
// factory took them over (same decisions, byte for byte).
void apply(RotationPlanner& p, const SolverOptions& opt)
{
  if (opt.max_dist_tables) p.set_max_dist_tables(opt.max_dist_tables);
  if (!opt.headings.empty()) p.set_headings(opt.headings);
  p.set_back_last(opt.back_last);
  p.set_pocket_exit(opt.pocket_exit);
  if (!opt.guidance.uniform()) p.set_guidance(opt.guidance);
}

std::unique_ptr<RealtimePlanner> make_rotation(Solver s, const Graph& g, const Config& starts, const Config& goals,
                                               const SolverOptions& opt, GoalTest test)
{
  if (s == Solver::Epibt) {
    auto p = std::make_unique<Epibt>(g, starts, goals, EpibtOptions{}, std::move(test), opt.heading);
    apply(*p, opt);
    EpibtOptions o = opt.epibt;
    o.seed = opt.seed;
    p->set_options(o);
    return p;
  }
  if (s == Solver::Wppl) {
    auto p = std::make_unique<Wppl>(g, starts, goals, opt.seed, std::move(test), opt.heading);
    apply(*p, opt);
    p->set_options(opt.wppl);
    return p;
  }
  auto p = std::make_unique<RotationPibt>(g, starts, goals, opt.seed, std::move(test), opt.heading);
  apply(*p, opt);
  return p;
}

}  // namespace

const char* to_string(Solver s)
{
  switch (s) {
    case Solver::Pibt: return "pibt";
    case Solver::Lacam: return "lacam";
    case Solver::RtLacam: return "rtlacam";
    case Solver::Naive: return "naive";
    case Solver::CsPibt: return "cspibt";
    case Solver::PibtRot: return "pibt-rot";
    case Solver::Epibt: return "epibt";
    case Solver::Wppl: return "wppl";
  }
  return "?";
}

std::vector<std::string> solver_list(bool realtime_only, bool cell_only)
{
  std::vector<std::string> out;
  for (Solver s : kAll)
    if ((!realtime_only || is_realtime(s)) && (!cell_only || !plans_rotation(s))) out.emplace_back(to_string(s));
  return out;
}

std::string solver_names(bool realtime_only, bool cell_only)
{
  std::string out;
  for (const std::string& n : solver_list(realtime_only, cell_only)) out += (out.empty() ? "" : " | ") + n;
  return out;
}

Solver parse_solver(const std::string& name)
{
  for (Solver s : kAll)
    if (name == to_string(s)) return s;
  throw std::invalid_argument("unknown solver '" + name + "' (" + solver_names() + ")");
}

std::unique_ptr<RealtimePlanner> make_planner(Solver s, const Graph& g, const Config& starts, const Config& goals,
                                              const SolverOptions& opt, GoalTest test)
{
  if (needs_policy(s) && !opt.pref) throw std::invalid_argument("solver cspibt needs a policy");
  if (plans_rotation(s)) return make_rotation(s, g, starts, goals, opt, std::move(test));
  LacamOptions lo = opt.lacam;
  lo.seed = opt.seed;
  std::unique_ptr<RealtimePlanner> p;
  switch (s) {
    case Solver::RtLacam: p = std::make_unique<RtLacam>(g, starts, goals, lo, opt.pref, std::move(test), opt.dist_cache); break;
    case Solver::Naive:
      p = std::make_unique<NaiveRtLacam>(g, starts, goals, lo, opt.pref, std::move(test), opt.dist_cache);
      break;
    case Solver::Pibt:
    case Solver::CsPibt: p = std::make_unique<PibtPlanner>(g, starts, goals, lo, opt.pref, std::move(test), opt.dist_cache); break;
    default: throw std::invalid_argument("solver lacam is not a real-time planner (plan once: run_full_horizon)");
  }
  if (opt.max_dist_tables) p->set_max_dist_tables(opt.max_dist_tables);
  return p;
}

}  // namespace planner
