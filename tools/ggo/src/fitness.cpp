#include "ggo/fitness.hpp"

#include "planner/movingai.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/lorr_problem.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/solver.hpp"

namespace ggo {

Problem load_problem(const std::string& path)
{
  const tasks::LorrProblem lp = tasks::load_lorr_problem(path);
  Problem pr;
  pr.name = lp.name;
  pr.g = planner::load_map(lp.map_file);
  pr.starts = tasks::load_lorr_agents(lp.agent_file, pr.g, lp.team_size);
  pr.tasks = std::make_shared<const tasks::TaskFile>(tasks::load_lorr_tasks(lp.task_file, pr.g));
  pr.steps = lp.simulation_time;
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
  opt.guidance = gd;
  opt.epibt = ep;
  const tasks::LifelongResult r = tasks::run_lifelong(pr.g, pr.starts, tm, tasks::kEpibtSolver, seed, opt);
  Evaluation e;
  e.throughput = static_cast<double>(r.errands_finished) / static_cast<double>(opt.steps);
  e.planner_errors = r.planner_errors;
  e.cpu_p99_ms = tasks::summarize(r.planner_cpu_ms).p99;
  return e;
}

}  // namespace ggo
