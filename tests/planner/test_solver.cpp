// The planner factory (planner/solver.hpp): names <-> Solver, the real-time planners it
// builds (each one solving a small instance with valid moves), and its refusals; the rotation
// solvers' options by the YAML's planner.rotation names (planner/rotation_settings.hpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "grid.hpp"
#include "planner/rotation_settings.hpp"
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

TEST(Solver, RotationSettingsByTheYamlKeys)
{
  const Graph g = test::grid({"....", "...."});
  // Value-initialised: the planners' own defaults, applied or not.
  SolverOptions plain, o;
  apply(RotationSettings{}, g, o);
  EXPECT_TRUE(o.guidance.uniform());
  EXPECT_EQ(o.epibt.tf.on, plain.epibt.tf.on);
  EXPECT_EQ(o.epibt.depth, plain.epibt.depth);
  EXPECT_EQ(o.epibt.revisit, plain.epibt.revisit);
  EXPECT_EQ(o.epibt.priority, plain.epibt.priority);
  EXPECT_EQ(o.wppl.window, plain.wppl.window);
  EXPECT_EQ(o.back_last, plain.back_last);
  // rtlacam-lifelong's: arrows for pibt-rot and epibt, none for wppl; traffic flow for epibt.
  EXPECT_EQ(RotationSettings::lifelong(Solver::PibtRot).guidance, "arrows");
  EXPECT_EQ(RotationSettings::lifelong(Solver::Epibt).guidance, "arrows");
  EXPECT_EQ(RotationSettings::lifelong(Solver::Wppl).guidance, "none");
  EXPECT_TRUE(RotationSettings::lifelong(Solver::Epibt).traffic_flow);
  EXPECT_FALSE(RotationSettings::lifelong(Solver::PibtRot).traffic_flow);
  // Every key reaches its field.
  RotationSettings s;
  s.back_last = s.pocket_exit = s.leavers_first = false;
  s.guidance = "arrows";
  s.traffic_flow = true;
  s.depth = 4;
  s.lns_rounds = 0;
  s.revisit = 10;
  s.priority = "age";
  s.window = 9;
  s.neighbourhood = 2;
  apply(s, g, o);
  EXPECT_FALSE(o.back_last || o.pocket_exit || o.epibt.pocket_exit || o.epibt.leavers_first);
  EXPECT_FALSE(o.guidance.uniform());
  EXPECT_TRUE(o.epibt.tf.on);
  EXPECT_EQ(o.epibt.depth, 4);
  EXPECT_EQ(o.epibt.lns_rounds, 0);
  EXPECT_EQ(o.epibt.revisit, 10);
  EXPECT_EQ(o.epibt.priority, EpibtOptions::Priority::Age);
  EXPECT_EQ(o.wppl.window, 9);
  EXPECT_EQ(o.wppl.neighbourhood, 2);
  // Which solver reads which key.
  EXPECT_EQ(rotation_key_misuse(Solver::Epibt, "window"), "only with solver wppl, not epibt");
  EXPECT_EQ(rotation_key_misuse(Solver::Wppl, "revisit"), "only with solver epibt, not wppl");
  EXPECT_EQ(rotation_key_misuse(Solver::Epibt, "back_last").rfind("only with solver pibt-rot or wppl", 0), 0u);
  EXPECT_EQ(rotation_key_misuse(Solver::RtLacam, "guidance"), "only with a rotation solver (pibt-rot | epibt | wppl), not rtlacam");
  for (const std::string& k : rotation_keys()) EXPECT_NE(rotation_key_misuse(Solver::Pibt, k), "") << k;
  for (const char* k : {"guidance", "guidance_costs", "pocket_exit"})
    for (Solver r : {Solver::PibtRot, Solver::Epibt, Solver::Wppl}) EXPECT_EQ(rotation_key_misuse(r, k), "") << k;
  EXPECT_THROW(rotation_key_misuse(Solver::Epibt, "dpeth"), std::invalid_argument);
  // Ranges; costs count only with arrows.
  s.depth = 7;
  EXPECT_EQ(check(s), "depth: must be in 3..5, got 7");
  EXPECT_THROW(apply(s, g, o), std::invalid_argument);
  s.depth = 3;
  s.guidance_costs = {1, 0, 1};
  EXPECT_EQ(check(s), "guidance_costs[1]: must be in 1..60, got 0");
  s.guidance = "none";
  EXPECT_EQ(check(s), "");
}
