#include "tasks/lifelong_runner.hpp"

#include <algorithm>
#include <cmath>

#include "planner/validator.hpp"
#include "tasks/lifelong_goal.hpp"
#include "tasks/solver.hpp"

namespace tasks {

using planner::Clock;
using planner::ms_since;

std::vector<Event> advance_epoch(TaskManager& tasks, planner::RealtimePlanner& p, long t)
{
  std::vector<Event> events = tasks.update(t, p.current());
  if (!events.empty()) p.set_goals(tasks.goals(), lifelong_goal_test(tasks, p.current()));
  return events;
}

PlannerTimes summarize(std::vector<double> ms)
{
  PlannerTimes s;
  if (ms.empty()) return s;
  std::sort(ms.begin(), ms.end());
  double sum = 0;
  for (double x : ms) sum += x;
  s.mean = sum / static_cast<double>(ms.size());
  // Nearest-rank percentiles.
  auto pct = [&](double q) {
    const size_t k = static_cast<size_t>(std::ceil(q * static_cast<double>(ms.size())));
    return ms[std::min(ms.size() - 1, k > 0 ? k - 1 : 0)];
  };
  s.p50 = pct(0.50);
  s.p99 = pct(0.99);
  s.max = ms.back();
  return s;
}

LifelongResult run_lifelong(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                            const std::string& solver, uint64_t seed, const LifelongOptions& opt)
{
  LifelongResult r;
  const auto wall0 = Clock::now();
  auto t0 = Clock::now();
  tasks.start(starts);
  auto p = make_planner(solver, g, starts, tasks.goals(), lifelong_goal_test(tasks, starts), seed, opt.pref, opt.keep_priorities, opt.refine);
  r.setup_ms = ms_since(t0);
  r.epochs = 1;

  double carry_ms = 0;  // set_goals at the end of the last step: planning for this one
  for (long t = 1; t <= opt.steps; ++t) {
    StepRecord rec;
    rec.t = t;
    rec.epoch = r.epochs;
    t0 = Clock::now();
    p->search(opt.budget);
    const planner::Config next = p->next();
    rec.planner_ms = ms_since(t0) + carry_ms;
    rec.explored = p->explored();

    const std::string err = planner::Validator::check_transition(g, p->current(), next);
    if (!err.empty()) {
      if (r.planner_errors++ == 0) r.first_error = "step " + std::to_string(t) + ": " + err;
    }
    p->commit();

    // advance_epoch, split to time the task layer apart from the planner.
    t0 = Clock::now();
    const std::vector<Event> ev = tasks.update(t, p->current());
    r.task_ms += ms_since(t0);
    t0 = Clock::now();
    if (!ev.empty()) p->set_goals(tasks.goals(), lifelong_goal_test(tasks, p->current()));
    carry_ms = ev.empty() ? 0.0 : ms_since(t0);
    if (!ev.empty()) ++r.epochs;
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
  return r;
}

}  // namespace tasks
