// The planner factory (planner/solver.hpp): names <-> Solver, the real-time planners it
// builds (each one solving a small instance with valid moves), and its refusals.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "grid.hpp"
#include "planner/solver.hpp"
#include "planner/validator.hpp"

using namespace planner;

namespace {

// A stand-in for a learned policy: moves nearer the goal (Manhattan) first.
struct TowardGoal : ActionPreference {
  const Graph& g;
  Config goals;
  explicit TowardGoal(const Graph& graph) : g(graph) {}
  void set_goals(const Config& gs) override { goals = gs; }
  float score(int i, Vertex, Vertex to, Rng&) override
  {
    return static_cast<float>(std::abs(g.cell_x(to) - g.cell_x(goals[i])) + std::abs(g.cell_y(to) - g.cell_y(goals[i])));
  }
};

}  // namespace

TEST(Solver, NamesRoundTrip)
{
  EXPECT_EQ(solver_names(), "pibt | lacam | rtlacam | naive | cspibt | pibt-rot | epibt | wppl");
  EXPECT_EQ(solver_names(true), "pibt | rtlacam | naive | cspibt | pibt-rot | epibt | wppl");
  EXPECT_EQ(solver_names(true, true), "pibt | rtlacam | naive | cspibt");
  for (const std::string& n : solver_list()) EXPECT_EQ(to_string(parse_solver(n)), n);
  EXPECT_EQ(solver_list(true).size(), solver_list().size() - 1);
  EXPECT_TRUE(needs_policy(Solver::CsPibt));
  EXPECT_FALSE(needs_policy(Solver::RtLacam));
  EXPECT_FALSE(is_realtime(Solver::Lacam));
  for (const char* n : {"pibt-rot", "epibt", "wppl"}) EXPECT_TRUE(plans_rotation(parse_solver(n))) << n;
  for (const std::string& n : solver_list(false, true)) EXPECT_FALSE(plans_rotation(parse_solver(n))) << n;
}

TEST(Solver, UnknownNameListsTheSolvers)
{
  try {
    parse_solver("magic");
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown solver 'magic' (pibt | lacam | rtlacam | naive | cspibt | pibt-rot | epibt | wppl)");
  }
  EXPECT_THROW(parse_solver("RTLACAM"), std::invalid_argument);
}

TEST(Solver, EveryRealtimeSolverReachesTheGoalsWithValidMoves)
{
  // Two agents that must pass each other in a corridor with one siding.
  const Graph g = test::grid({"....", ".#.."});
  const Config starts{g.at(0, 0), g.at(3, 0)}, goals{g.at(3, 0), g.at(0, 0)};
  for (const std::string& name : solver_list(true)) {
    SCOPED_TRACE(name);
    const Solver s = parse_solver(name);
    TowardGoal pref(g);
    SolverOptions opt;
    opt.pref = needs_policy(s) ? &pref : nullptr;
    auto p = make_planner(s, g, starts, goals, opt);
    EXPECT_EQ(p->name(), name == "cspibt" ? "pibt" : name);
    Validator v(g, starts, goals);
    for (int t = 0; t < 100 && !p->at_goal(); ++t) {
      p->search(Budget::expansion_count(10));
      ASSERT_TRUE(v.step(p->next())) << v.error();
      p->commit();
    }
    EXPECT_TRUE(p->at_goal());
  }
}

TEST(Solver, RefusesLacamAndCspibtWithoutAPolicy)
{
  const Graph g = test::grid({"..."});
  const Config s{g.at(0, 0)}, t{g.at(2, 0)};
  EXPECT_THROW(make_planner(Solver::Lacam, g, s, t), std::invalid_argument);
  try {
    make_planner(Solver::CsPibt, g, s, t);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "solver cspibt needs a policy");
  }
}

TEST(Solver, AppliesEveryRotationOptionAtConstruction)
{
  // The options reach the planner without a cast by the caller: epibt's seed and depth,
  // wppl's window, the starting heading and the guidance.
  const Graph g = test::grid({"....", "...."});
  const Config starts{g.at(0, 0)}, goals{g.at(3, 1)};
  SolverOptions opt;
  opt.seed = 7;
  opt.heading = 3;
  opt.epibt.depth = 4;
  opt.wppl.window = 9;
  auto e = make_planner(Solver::Epibt, g, starts, goals, opt);
  const auto& ep = dynamic_cast<const Epibt&>(*e);
  EXPECT_EQ(ep.options().depth, 4);
  EXPECT_EQ(ep.options().seed, 7u);
  EXPECT_EQ(ep.headings(), std::vector<int>{3});
  auto w = make_planner(Solver::Wppl, g, starts, goals, opt);
  EXPECT_EQ(dynamic_cast<const Wppl&>(*w).options().window, 9);
  EXPECT_EQ(dynamic_cast<const RotationPlanner&>(*w).headings(), std::vector<int>{3});
  // A rotation planner's first step from heading 3 (north) toward a goal to the east and
  // south: it must turn before it can move, so the cell stays.
  auto r = make_planner(Solver::PibtRot, g, starts, goals, opt);
  r->search(Budget::expansion_count(1));
  EXPECT_EQ(r->next(), starts);
}

TEST(Solver, RotationSolversTakeOneStartHeadingPerRobot)
{
  // SolverOptions::headings (SUMO AGVs face along their start lanes) overrides `heading`
  // robot by robot: a robot already facing its goal moves at once, one facing away turns.
  const Graph g = test::grid({"....", "...."});
  const Config starts{g.at(1, 0), g.at(1, 1)}, goals{g.at(3, 0), g.at(3, 1)};
  SolverOptions opt;
  opt.heading = 3;
  opt.headings = {0, 2};  // east (toward its goal), west (away)
  for (Solver s : {Solver::PibtRot, Solver::Epibt, Solver::Wppl}) {
    SCOPED_TRACE(to_string(s));
    auto p = make_planner(s, g, starts, goals, opt);
    EXPECT_EQ(p->rotation()->headings(), opt.headings);
    p->search(Budget::expansion_count(10));
    EXPECT_EQ(p->rotation()->actions()[0], 'F');
    EXPECT_NE(p->rotation()->actions()[1], 'F');
  }
  opt.headings = {0};
  EXPECT_THROW(make_planner(Solver::PibtRot, g, starts, goals, opt), std::invalid_argument);
  opt.headings = {0, 4};
  EXPECT_THROW(make_planner(Solver::Epibt, g, starts, goals, opt), std::invalid_argument);
}
