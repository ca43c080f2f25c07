#include "planner/solver.hpp"

#include <stdexcept>

#include "planner/lacam/naive_rt_lacam.hpp"
#include "planner/lacam/pibt_planner.hpp"
#include "planner/lacam/rt_lacam.hpp"

namespace planner {
namespace {

constexpr Solver kAll[] = {Solver::Pibt, Solver::Lacam, Solver::RtLacam, Solver::Naive, Solver::CsPibt};

}  // namespace

const char* to_string(Solver s)
{
  switch (s) {
    case Solver::Pibt: return "pibt";
    case Solver::Lacam: return "lacam";
    case Solver::RtLacam: return "rtlacam";
    case Solver::Naive: return "naive";
    case Solver::CsPibt: return "cspibt";
  }
  return "?";
}

std::vector<std::string> solver_list(bool realtime_only)
{
  std::vector<std::string> out;
  for (Solver s : kAll)
    if (!realtime_only || is_realtime(s)) out.emplace_back(to_string(s));
  return out;
}

std::string solver_names(bool realtime_only)
{
  std::string out;
  for (const std::string& n : solver_list(realtime_only)) out += (out.empty() ? "" : " | ") + n;
  return out;
}

Solver parse_solver(const std::string& name)
{
  for (Solver s : kAll)
    if (name == to_string(s)) return s;
  throw std::invalid_argument("unknown solver '" + name + "' (" + solver_names() + ")");
}

std::unique_ptr<RealtimePlanner> make_planner(Solver s, const Graph& g, const Config& starts, const Config& goals,
                                              const LacamOptions& opt, ActionPreference* pref, GoalTest test)
{
  if (needs_policy(s) && !pref) throw std::invalid_argument("solver cspibt needs a policy");
  switch (s) {
    case Solver::RtLacam: return std::make_unique<RtLacam>(g, starts, goals, opt, pref, std::move(test));
    case Solver::Naive: return std::make_unique<NaiveRtLacam>(g, starts, goals, opt, pref, std::move(test));
    case Solver::Pibt:
    case Solver::CsPibt: return std::make_unique<PibtPlanner>(g, starts, goals, opt, pref, std::move(test));
    case Solver::Lacam: break;
  }
  throw std::invalid_argument("solver lacam is not a real-time planner (plan once: run_full_horizon)");
}

}  // namespace planner
