#include "tasks/lifelong_exec.hpp"

#include <algorithm>
#include <stdexcept>

#include "planner/stop_signal.hpp"
#include "planner/validator.hpp"
#include "tasks/lifelong_goal.hpp"
#include "tasks/solver.hpp"

namespace tasks {

using planner::Clock;
using planner::ms_since;

LifelongExecResult run_lifelong_exec(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                                     const std::string& solver, uint64_t seed, const LifelongOptions& opt,
                                     const executor::DelaySpec& delays, const executor::ExecOptions& exec)
{
  if (is_rotation_native(solver))  // its steps are LoRR actions, not cell moves an executor can delay
    throw std::invalid_argument("solver " + solver + " has its own rotation actions: no --executor");
  LifelongExecResult out;
  LifelongResult& r = out.life;
  const auto wall0 = Clock::now();
  auto t0 = Clock::now();
  tasks.start(starts);
  auto p = make_planner(solver, g, starts, tasks.goals(), lifelong_goal_test(tasks, starts), seed, opt.pref,
                        opt.keep_priorities, opt.refine);
  r.setup_ms = ms_since(t0);
  r.epochs = 1;
  executor::GraphExecution ex(*p, delays, exec);
  long long last_completion = 0;
  double carry_ms = 0;
  for (long t = 1; t <= opt.steps; ++t) {
    if (planner::stop_signal()) break;  // SIGINT / SIGTERM: end here, the caller writes the log
    StepRecord rec;
    rec.t = t;
    rec.epoch = r.epochs;
    const planner::Config before = ex.positions();
    t0 = Clock::now();
    ex.tick(opt.budget);  // search + commits + execution (the execution part is negligible)
    rec.planner_ms = ms_since(t0) + carry_ms;
    rec.explored = p->explored();
    const std::string err = planner::Validator::check_transition(g, before, ex.positions());
    if (!err.empty() && r.planner_errors++ == 0) r.first_error = "step " + std::to_string(t) + ": " + err;

    t0 = Clock::now();
    const std::vector<Event> ev = tasks.update(t, ex.positions());
    r.task_ms += ms_since(t0);
    t0 = Clock::now();
    if (!ev.empty()) {
      p->set_goals(tasks.goals(), lifelong_goal_test(tasks, p->current()));
      ++r.epochs;
      last_completion = t;
    }
    out.max_gap = std::max(out.max_gap, t - last_completion);
    carry_ms = ev.empty() ? 0.0 : ms_since(t0);
    rec.completed = static_cast<int>(ev.size());
    rec.new_epoch = !ev.empty();
    r.events.insert(r.events.end(), ev.begin(), ev.end());
    r.planner_ms.push_back(rec.planner_ms);
    r.steps = t;
    if (opt.on_step) opt.on_step(rec);
  }
  r.errands_finished = tasks.errands_finished();
  r.tasks_finished = tasks.tasks_finished();
  r.expansions = p->expansions();
  r.wall_ms = ms_since(wall0);
  out.exec = ex.stats();
  return out;
}

}  // namespace tasks
