#include "ggo/fitness.hpp"

#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_instance.hpp"
#include "tasks/roundrobin.hpp"
#include "planner/solver.hpp"

namespace ggo {

Problem load_problem(const std::string& path)
{
  tasks::LorrInstance in = tasks::load_lorr_instance(path);
  Problem pr;
  pr.name = in.problem.name;
  pr.g = std::move(in.g);
  pr.starts = std::move(in.starts);
  pr.tasks = std::move(in.tasks);
  pr.steps = in.problem.simulation_time;
  return pr;
}

Evaluation evaluate(const Problem& pr, const planner::Guidance& gd, long steps, uint64_t seed,
                    const planner::Epibt::Options& ep)
{
  tasks::RoundRobin tm(pr.tasks);
  tasks::LifelongOptions opt;
  opt.steps = steps > 0 ? steps : pr.steps;
  opt.action_model = tasks::ActionModel::Rotation;
  opt.budget = planner::Budget::time_ms(1000);
  opt.solver.guidance = gd;
  opt.solver.epibt = ep;
  const tasks::LifelongResult r = tasks::run_lifelong(pr.g, pr.starts, tm, "epibt", seed, opt);
  Evaluation e;
  e.throughput = static_cast<double>(r.errands_finished) / static_cast<double>(opt.steps);
  e.planner_errors = r.planner_errors;
  e.cpu_p99_ms = tasks::summarize(r.planner_cpu_ms).p99;
  return e;
}

}  // namespace ggo
