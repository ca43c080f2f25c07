// Solves a MovingAI instance with an installed rtlacam (the tasks layer's factory, a
// learned policy for CS-PIBT's move order) and validates every move.
// Usage: consumer MAP SCEN N WEIGHTS
#include <iostream>
#include <string>

#include "planner/movingai.hpp"
#include "planner/validator.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"
#include "planner/solver.hpp"

int main(int argc, char** argv)
{
  if (argc != 5) return 2;
  const planner::Graph g = planner::load_map(argv[1]);
  const planner::Instance ins = planner::load_scen(argv[2], g, std::stoi(argv[3]));
  const policy::Model model = policy::load_weights(argv[4]);
  policy::PolicyPreference pref(g, model, ins.goals);
  planner::SolverOptions opt;
  opt.pref = &pref;
  auto p = planner::make_planner(planner::Solver::RtLacam, g, ins.starts, ins.goals, opt);
  planner::Validator v(g, ins.starts, ins.goals);
  for (int t = 0; t < 10000 && !p->at_goal(); ++t) {
    p->search(planner::Budget::expansion_count(100));
    if (!v.step(p->next())) {
      std::cerr << "consumer: invalid move: " << v.error() << "\n";
      return 3;
    }
    p->commit();
  }
  std::cout << "solved=" << p->at_goal() << " steps=" << v.steps() << " soc=" << v.sum_of_costs() << "\n";
  return p->at_goal() ? 0 : 4;
}
