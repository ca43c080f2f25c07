// rtlacam-check: the project's validator on a plan in the LaCAM result format, whoever wrote
// it (rtlacam-bench --out, lacam, lacam3 -o): one checker and one cost for every planner
// that scripts/peer_bench.py compares. Prints one JSON line: valid, error, soc (standard,
// up to each agent's last arrival), sum_of_loss, makespan, soc_lb. Exit 3 on an invalid plan.
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "planner/error.hpp"
#include "planner/instance.hpp"
#include "planner/movingai.hpp"
#include "planner/plan_io.hpp"
#include "planner/validator.hpp"

using namespace planner;

int main(int argc, char** argv)
{
  CLI::App app{"Checks a plan (LaCAM result format) against a MovingAI instance and prints its costs"};
  std::string map_file, scen_file, plan_file;
  int agents = 0;
  app.add_option("--map", map_file, "MovingAI .map")->required();
  app.add_option("--scen", scen_file, "MovingAI .scen")->required();
  app.add_option("-N,--agents", agents, "the first N agents of the scen")->required()->check(cli::positive());
  app.add_option("--plan", plan_file, "result file (its solution= section)")->required();
  cli::add_version(app, "rtlacam-check");
  RTLACAM_PARSE(app, argc, argv);
  try {
    const Graph g = load_map(map_file);
    const Instance ins = load_scen(scen_file, g, agents);
    std::ifstream in(plan_file);
    if (!in) throw input_error(plan_file, 0, "cannot read file");
    const std::vector<Config> plan = read_plan(in, g, plan_file);
    nlohmann::json j;
    std::string err = validate_plan(g, ins.starts, ins.goals, plan, true);
    for (size_t t = 0; err.empty() && t < plan.size(); ++t)
      if (plan[t].size() != ins.starts.size())
        err = "timestep " + std::to_string(t) + " has " + std::to_string(plan[t].size()) + " agents";
    Validator v(g, ins.starts, ins.goals);
    for (size_t t = 1; err.empty() && t < plan.size(); ++t) v.step(plan[t]);
    j["valid"] = err.empty();
    j["error"] = err;
    j["soc"] = err.empty() ? v.sum_of_costs() : 0;
    j["sum_of_loss"] = err.empty() ? v.sum_of_loss() : 0;
    j["makespan"] = err.empty() ? v.steps() : 0;
    j["soc_lb"] = ins.soc_lower_bound(g);
    std::cout << j.dump() << std::endl;
    return err.empty() ? cli::kOk : cli::kInvalidPlan;
  } catch (const InputError& e) {
    std::cerr << "rtlacam-check: " << e.what() << std::endl;
    return cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "rtlacam-check: error: " << e.what() << std::endl;
    return cli::kRuntimeError;
  }
}
