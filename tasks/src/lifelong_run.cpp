#include "tasks/lifelong_run.hpp"

#include <algorithm>
#include <stdexcept>

#include "executor/rotation_execution.hpp"
#include "planner/rotation/rotation_planner.hpp"
#include "planner/validator.hpp"
#include "tasks/lifelong_goal.hpp"

namespace tasks {

using planner::Clock;
using planner::ms_since;
using planner::thread_cpu_ms;  // planning work, told apart from time the thread was preempted

namespace {

bool has_pending(const TaskManager& tasks, const planner::Config& at)
{
  for (int a = 0; a < tasks.num_agents(); ++a)
    if (tasks.busy(a) && at[a] != tasks.goals()[a]) return true;
  return false;
}

}  // namespace

LifelongRun::LifelongRun(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                         const std::string& solver, uint64_t seed, const LifelongOptions& opt)
    : g_(g), tasks_(tasks), opt_(opt), kind_(planner::parse_solver(solver)),
      sb_(opt.budget, opt.expansion_deviations, opt.precompute_share, opt.bound_queries)
{
  r_.action_model = opt.action_model;
  r_.starts = starts;
  rotation_ = opt.action_model == ActionModel::Rotation;
  // The rotation solvers plan the robots' actions themselves: no cell plan, no RotationExecution.
  native_ = planner::plans_rotation(kind_);
  if (native_ && !rotation_)
    throw std::invalid_argument("solver " + solver + " plans rotation actions: it needs --action-model rotation");
  prefetch_ = opt.prefetch && !native_;  // the prefetch grows cell tables, which the rotation solvers do not read
  letters_ = opt.record_actions && g.is_grid();
  if (letters_) r_.actions.assign(starts.size(), std::string());
  wall0_ = Clock::now();
  const auto t0 = Clock::now();
  // One distance cache for the task layer, the heading preference and the planner.
  cache_ = std::make_shared<planner::DistCache>(g, opt.max_dist_tables ? opt.max_dist_tables : 2 * starts.size() + 256);
  epochs_.start(g, starts, std::make_unique<FreeFlowBound>(cache_), cache_);  // free flow: a move per step
  // Rotation: PIBT breaks distance ties by the turns a move needs (unless a policy orders moves).
  planner::ActionPreference* pref = opt.solver.pref;
  if (rotation_ && !native_ && !pref && opt.heading_ties) {
    heading_ = std::make_unique<HeadingPreference>(g, starts, opt.heading_cost);
    heading_->share_dist_cache(cache_);
    pref = heading_.get();
  }
  planner::SolverOptions so = opt.solver;
  so.seed = seed;
  so.pref = pref;
  // A lifelong run visits thousands of goal cells: keep the tables in use plus a few hundred
  // recent ones, not one per cell ever visited ((cell, heading) tables are 2x a cell table).
  so.max_dist_tables = native_ ? starts.size() + 256 : 2 * starts.size() + 256;
  p_ = planner::make_planner(kind_, g, starts, tasks_.goals(), so, lifelong_goal_test(tasks_, starts));
  p_->share_dist_cache(cache_);
  rot_ = p_->rotation();  // pibt-rot, epibt, wppl: their actions, headings and (cell, heading) tables
  if (prefetch_) {
    // Preprocessing (LoRR allows it before the first step): the first goals' tables reach
    // the agents, the next goals' reach the first. Later wants are met in the steps' spare time.
    std::vector<planner::DistCache::Want> first;
    for (size_t i = 0; i < starts.size(); ++i) first.push_back({tasks_.goals()[i], starts[i]});
    cache_->prefetch(first);
    cache_->precompute(Clock::time_point::max());
    epochs_.prefetch(*cache_, p_->current());
    cache_->precompute(Clock::time_point::max());
  }
  rot_prefetch_ = rot_ && opt.prefetch;
  if (rot_prefetch_) {  // preprocessing: the next goals' tables (the first ones grew in set_goals)
    epochs_.prefetch(*rot_);
    rot_->precompute(Clock::time_point::max());
  }
  if (opt.graph_execution) {
    // A cell plan under the rotation model runs on RotationExecution; the rotation solvers'
    // plans run on GraphExecution with executed headings (graph_execution.hpp).
    if (rotation_ && !native_)
      throw std::invalid_argument("solver " + solver +
                                  " under the rotation model runs its cell plan on the rotation executor: no --executor (the "
                                  "rotation solvers pibt-rot, epibt, wppl take one)");
    auto ge = std::make_unique<executor::GraphExecution>(*p_, opt.delays, opt.exec);
    graph_ = ge.get();
    exec_ = std::move(ge);
  } else if (rotation_ && !native_) {
    exec_ = std::make_unique<executor::RotationExecution>(g, starts, opt.rotation_window);
  }
  // RT-LaCAM may make no expansion in a step: the agents follow the tree or wait.
  may_skip_ = opt.skip_late_search && sb_.bounded && kind_ == planner::Solver::RtLacam;
  sb_.skip_late = true;  // --skip-late-search: a step with less than one expansion's bound left
  r_.setup_ms = ms_since(t0);
}

// Work for the steps' spare time: the cell tables' queue (prefetched goals and tables that
// bounded queries estimated, with or without prefetch) and the rotation solvers' own tables
// (their queue also holds the tables their bounded queries met late, prefetch or not).
size_t LifelongRun::pending() const { return cache_->pending() + (rot_ ? rot_->pending() : 0); }

void LifelongRun::precompute(Clock::time_point deadline)
{
  cache_->precompute(deadline);
  if (rot_) rot_->precompute(deadline);
}

// One deadline for all of a step's planning: queries past it answer lower bounds instead of
// growing tables (dist_cache.hpp). Off (bound_queries false, or no positive time budget: a
// 0 ms budget means one expansion per step in tests): every query exact.
void LifelongRun::bound_queries(planner::DistCache::Deadline d)
{
  if (sb_.bounded) cache_->set_deadline(d);
  if (sb_.bounded && rot_) rot_->set_deadline(d);  // the rotation solvers' (cell, heading) tables likewise
}

void LifelongRun::error(long t, const std::string& what)
{
  if (r_.planner_errors++ == 0) {
    r_.first_error = "step " + std::to_string(t) + what;
    r_.first_error_t = t;
  }
}

const StepRecord& LifelongRun::step()
{
  Step s;
  open(s);
  precompute_first(s);
  plan(s);
  spare(s);
  account(s);
  commit(s);
  const planner::Config& real = execute(s);
  complete(s, real);
  record(s);
  last_ = s.rec;
  return last_;
}

void LifelongRun::open(Step& s)
{
  s.rec.t = ++t_;
  s.rec.epoch = r_.epochs;
  s.b = sb_.left();  // the epoch start is inside the step's budget
  s.t0 = Clock::now();
  s.cpu0 = thread_cpu_ms();
  s.pops0 = cache_->counters().query_pops;
  s.end = s.b.deadline_from(s.t0);
  bound_queries(s.end);
  s.reserve = sb_.reserve();
  s.plan_now = !exec_ || graph_ || exec_->can_accept();  // graph_: search on while the window is full
  if (!s.plan_now) ++r_.window_full;
  // No room left for one expansion (the epoch start took it): no search this step
  // (StepBudget::skip: at most max_skips in a row, the search keeps making progress and its
  // cost estimate fresh whatever the budget).
  const bool skip = s.plan_now && sb_.skip(may_skip_, opt_.budget.ms, s.b.ms);
  s.search_now = s.plan_now && !skip;
  if (skip) {
    r_.searches_skipped = sb_.searches_skipped;
    if (exec_) s.plan_now = false;  // the robots run their window; a wait would take a slot of it
  }
}

void LifelongRun::precompute_first(Step& s)
{
  if (!s.search_now || pending() == 0) return;
  // Tables first, up to the share: an expansion that meets an incomplete table would pay its
  // BFS anyway, all at once. It leaves room for the one expansion the search always makes,
  // and it overruns its deadline too (guard).
  precompute(planner::Budget::time_ms(std::max(0.0, sb_.precompute_ms(s.b.ms))).deadline_from(s.t0));
  s.rec.precompute_ms = ms_since(s.t0);
  s.b.ms = std::max(0.0, s.b.ms - s.rec.precompute_ms);
}

void LifelongRun::plan(Step& s)
{
  if (!s.search_now) {
    if (s.plan_now && !graph_) s.next = p_->next();
    return;
  }
  planner::Budget& b = s.b;
  const auto t1 = Clock::now();
  double c1 = thread_cpu_ms();
  // The rotation solvers plan a whole step in one call and check the deadline themselves:
  // give them the time left (an expansion-count call would run them without a clock).
  if (!sb_.bounded || rot_) {  // no time limit (or exact queries): the search's own loop
    b.ms = std::max(0.0, b.ms - s.reserve);  // it checks its deadline after each expansion
    if (sb_.bounded) bound_queries(b.deadline_from(t1));
    const uint64_t e0 = p_->expansions();
    p_->search(b);
    if (const uint64_t de = p_->expansions() - e0; de > 0) sb_.first.add((thread_cpu_ms() - c1) / static_cast<double>(de));
  } else {
    // The first expansion always (open() decided), measured alone; then the search goes on
    // while one more expansion's bound fits before the deadline (Budget::reserve_ms). Queries
    // stop growing tables where the first expansion's bound begins, as the search's own
    // deadline did.
    const auto end = b.deadline_from(t1);
    bound_queries(planner::Budget::time_ms(std::max(0.0, b.ms - s.reserve)).deadline_from(t1));
    uint64_t e0 = p_->expansions();
    p_->search(planner::Budget::expansion_count(1));
    double c = thread_cpu_ms();
    if (p_->expansions() > e0) sb_.first.add(c - c1);
    const CostEstimate& est = sb_.later.known() ? sb_.later : sb_.first;
    const double left = std::chrono::duration<double, std::milli>(end - Clock::now()).count();
    if (b.expansions > 1 && p_->expansions() > e0 && left > est.bound(sb_.deviations)) {
      e0 = p_->expansions();
      c1 = c;
      p_->search({left, b.expansions - 1, est.bound(sb_.deviations)});
      c = thread_cpu_ms();
      // The call's costliest expansion where the search tells it (RT-LaCAM), else the mean:
      // expansions that revisit a known configuration are cheap, new nodes are not.
      if (const uint64_t de = p_->expansions() - e0; de > 0)
        sb_.later.add(p_->max_expansion_ms() >= 0 ? p_->max_expansion_ms() : (c - c1) / static_cast<double>(de));
    }
  }
  if (!graph_) s.next = p_->next();  // graph_: commit() takes as many as its window has room for
}

void LifelongRun::spare(Step& s)
{
  if (pending() == 0 || Clock::now() >= s.end) return;
  const auto t1 = Clock::now();  // time left: the search ended early or the window is full
  precompute(s.end);
  s.rec.precompute_ms += ms_since(t1);
  // How far it ran past the deadline, when the deadline stopped it (not when it ran out of
  // work); a sample above a tenth of the budget is preemption, not work.
  if (pending() > 0) sb_.overrun.add(std::clamp(ms_since(s.end), 0.0, 0.1 * opt_.budget.ms));
}

void LifelongRun::account(Step& s)
{
  StepRecord& rec = s.rec;
  rec.planner_ms = ms_since(s.t0) + sb_.carry_ms;
  rec.planner_cpu_ms = thread_cpu_ms() - s.cpu0 + sb_.carry_cpu_ms;
  rec.query_pops = cache_->counters().query_pops - s.pops0 + sb_.carry_pops;
  rec.epoch_start_ms = sb_.carry_ms;
  rec.epoch_start_cpu_ms = sb_.carry_cpu_ms;
  if (rec.planner_ms > opt_.budget.ms + 0.05) ++r_.steps_over_budget;
  if (rec.planner_cpu_ms > opt_.budget.ms + 0.05) ++r_.steps_over_budget_cpu;
  rec.explored = p_->explored();
  bound_queries(planner::DistCache::Deadline::max());  // the task layer's queries: exact
}

void LifelongRun::commit(Step& s)
{
  if (!s.plan_now) return;
  const long t = s.rec.t;
  if (graph_) {  // fill the window, each committed step checked
    graph_->top_up([&](const planner::Config& from, const planner::Config& to) {
      const std::string err = planner::Validator::check_transition(g_, from, to);
      if (!err.empty()) error(t, ": " + err);
      if (rot_) {  // the planned actions too (the executed ones are checked in execute())
        const std::string bad = check_rotation_step(g_, from, rot_->headings(), rot_->actions(), to);
        if (!bad.empty()) error(t, ": " + bad);
      }
    });
    return;
  }
  const std::string err = planner::Validator::check_transition(g_, p_->current(), s.next);
  if (!err.empty()) error(t, ": " + err);
  if (letters_ && !rotation_)
    for (size_t i = 0; i < s.next.size(); ++i) r_.actions[i] += grid4_letter(g_, p_->current()[i], s.next[i]);
  if (rot_) {  // the actions themselves: forward into the cell ahead, turns and waits in place
    const std::string bad = check_rotation_step(g_, p_->current(), rot_->headings(), rot_->actions(), s.next);
    if (!bad.empty()) error(t, ": " + bad);
    if (letters_)
      for (size_t i = 0; i < s.next.size(); ++i) r_.actions[i] += rot_->actions()[i];
  }
  p_->commit();
  if (heading_) heading_->committed(p_->current());
}

const planner::Config& LifelongRun::execute(Step& s)
{
  if (!exec_) return p_->current();
  if (s.plan_now && !graph_) exec_->push(p_->current());
  const planner::Config before = exec_->positions();
  const std::vector<int> headed = graph_ && rot_ ? exec_->headings() : std::vector<int>{};
  exec_->step();
  // The executed step is checked like a planned one: cells, adjacency, vertex and swap conflicts.
  const std::string err = planner::Validator::check_transition(g_, before, exec_->positions());
  if (!err.empty()) error(s.rec.t, " (executed): " + err);
  if (graph_ && rot_) {  // and the robots' executed actions: forward into the cell ahead, turns in place
    const std::string bad = check_rotation_step(g_, before, headed, exec_->actions(), exec_->positions());
    if (!bad.empty()) error(s.rec.t, " (executed): " + bad);
  }
  if (letters_ && graph_ && !rot_) {  // what the agents executed this step (several commits may run at once)
    for (size_t i = 0; i < before.size(); ++i) r_.actions[i] += grid4_letter(g_, before[i], exec_->positions()[i]);
  } else if (letters_) {
    const std::string& act = exec_->actions();
    for (size_t i = 0; i < act.size(); ++i) r_.actions[i] += act[i];
  }
  return exec_->positions();
}

void LifelongRun::complete(Step& s, const planner::Config& real)
{
  // Errands complete on the robots' real cells (LifelongEpochs, the task layer's time); the
  // planner's new epoch starts at its own current configuration (the plan frontier under
  // rotation), timed apart as the next step's planning.
  bool replan = epochs_.complete(s.rec.t, real);
  const bool completed = !epochs_.completed().empty();
  const auto t0 = Clock::now();
  const double cpu0 = thread_cpu_ms();
  const uint64_t pops0 = cache_->counters().query_pops;
  // Rotation: the plan frontier runs ahead of the robots, so it can reach a goal before the
  // robot does. Its epoch's goal test then holds and RT-LaCAM would only wait; a new epoch at
  // the frontier (that agent no longer pending) keeps the others' plans going. The robot
  // still completes the errand when it physically gets there.
  replan = replan || (exec_ && !graph_ && s.plan_now && p_->at_goal() && has_pending(tasks_, p_->current()));
  // The epoch start is the next step's planning (StepBudget::epoch_start_ms; at 1 ms on
  // WAREHOUSE, none: the next step's precompute grows what it missed).
  bound_queries(planner::Budget::time_ms(sb_.epoch_start_ms()).deadline_from(t0));
  if (replan) epochs_.start_epoch(*p_);
  if (completed && prefetch_) epochs_.prefetch(*cache_, p_->current());
  if (completed && rot_prefetch_) epochs_.prefetch(*rot_);
  sb_.paid();  // this step counted its carry (account)
  if (replan) sb_.charge(ms_since(t0), thread_cpu_ms() - cpu0, cache_->counters().query_pops - pops0);
  epochs_.record(replan);
  epochs_.count(s.rec.t, real);  // goal ticks, station crowd, queue and parking counts (as the controller's)
  r_.counts = epochs_.counts();
  s.rec.completed = static_cast<int>(epochs_.completed().size());
  s.rec.new_epoch = completed;
}

void LifelongRun::record(Step& s)
{
  const StepRecord& rec = s.rec;
  r_.planner_ms.push_back(rec.planner_ms);
  r_.planner_cpu_ms.push_back(rec.planner_cpu_ms);
  r_.query_pops_max = std::max(r_.query_pops_max, rec.query_pops);
  r_.epoch_start_ms.push_back(rec.epoch_start_ms);
  r_.epoch_start_cpu_ms.push_back(rec.epoch_start_cpu_ms);
  r_.precompute_ms.push_back(rec.precompute_ms);
  // The rotation solvers: their (cell, heading) tables count beside the task layer's cell tables.
  const size_t rot_tables = rot_ ? rot_->dist().num_tables() : 0;
  r_.dist_tables_max = std::max(r_.dist_tables_max, cache_->num_tables() + rot_tables);
  if (rec.t % 16 == 0 || rec.t == opt_.steps)
    r_.dist_mb_max = std::max(r_.dist_mb_max, static_cast<double>(cache_->bytes() + (rot_ ? rot_->dist().bytes() : 0)) / (1 << 20));
  r_.steps = rec.t;
  if (opt_.on_step) opt_.on_step(rec);
}

LifelongResult LifelongRun::finish()
{
  cache_->set_deadline(planner::DistCache::Deadline::max());  // the task layer keeps the cache: exact again
  if (exec_) r_.final_headings = exec_->headings();
  if (rot_ && !graph_) r_.final_headings = rot_->headings();  // the robots' (with graph_: the executed ones)
  r_.dist_tables = cache_->num_tables() + (rot_ ? rot_->dist().num_tables() : 0);
  r_.dist_counters = cache_->counters();
  r_.ms_per_expansion = sb_.later.known() ? sb_.later.mean : sb_.first.mean;
  r_.ms_per_first_expansion = sb_.first.mean;
  r_.errands_finished = tasks_.errands_finished();
  r_.tasks_finished = tasks_.tasks_finished();
  r_.expansions = p_->expansions();
  // A run that could not progress said nothing (0 tasks, rc 0): an errand its agent cannot
  // reach (another component) or an epoch the planner proved unsolvable (a corridor swap).
  // Exact queries now (deadline cleared above); one table per distinct goal at most.
  const planner::Config& at = p_->current();
  const planner::Config& goals = p_->goals();
  for (size_t i = 0; i < at.size() && i < goals.size(); ++i)
    if (at[i] != goals[i] && cache_->table(goals[i])->at(at[i], g_) >= planner::DistCache::kInf) ++r_.unreachable_goals;
  r_.unsolvable_epoch = p_->exhausted();
  r_.wall_ms = ms_since(wall0_);
  return std::move(r_);
}

}  // namespace tasks
