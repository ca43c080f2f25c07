#include "tasks/lifelong_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "planner/stop_signal.hpp"
#include "planner/rotation/epibt.hpp"
#include "planner/rotation/rotation_pibt.hpp"
#include "planner/rotation/rotation_planner.hpp"
#include "planner/lacam/rt_lacam.hpp"
#include "planner/validator.hpp"
#include "planner/rotation/wppl.hpp"
#include "tasks/cost_estimate.hpp"
#include "tasks/heading_preference.hpp"
#include "tasks/lifelong_goal.hpp"
#include "tasks/rotation_executor.hpp"
#include "tasks/solver.hpp"

namespace tasks {

using planner::Clock;
using planner::ms_since;
using planner::thread_cpu_ms;  // planning work, told apart from time the thread was preempted

std::vector<Event> advance_epoch(TaskManager& tasks, planner::RealtimePlanner& p, long t)
{
  std::vector<Event> events = tasks.update(t, p.current());
  if (!events.empty()) p.set_goals(tasks.goals(), lifelong_goal_test(tasks, p.current()));
  return events;
}

namespace {

constexpr int kMaxSkips = 3;  // searches skipped in a row at most (skip_late_search)

bool has_pending(const TaskManager& tasks, const planner::Config& at)
{
  for (int a = 0; a < tasks.num_agents(); ++a)
    if (tasks.busy(a) && at[a] != tasks.goals()[a]) return true;
  return false;
}

// Queues the tables of the goals to come, most urgent first: agents nearest their current
// goal (at the plan frontier `at`). Each next goal's table must reach the current goal,
// where the agent will be when it gets the next one.
void prefetch_upcoming(const TaskManager& tasks, const planner::Config& at, planner::DistCache& cache)
{
  std::vector<std::pair<int32_t, planner::DistCache::Want>> order;
  for (const auto& u : tasks.upcoming()) {
    const planner::Vertex now = tasks.goals()[u.agent];
    order.push_back({cache.table(now)->at(at[u.agent], cache.graph()), {u.goal, now}});
  }
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<planner::DistCache::Want> wants;
  wants.reserve(order.size());
  for (const auto& o : order) wants.push_back(o.second);
  cache.prefetch(wants);
}

// pibt-rot: the same goals to come, for its own (cell, heading) tables; nearest agent first.
void prefetch_rotation(const TaskManager& tasks, planner::RotationPlanner& rot)
{
  std::vector<std::pair<uint16_t, planner::Vertex>> order;
  for (const auto& u : tasks.upcoming()) order.push_back({rot.h(u.agent), u.goal});
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<planner::Vertex> goals;
  goals.reserve(order.size());
  for (const auto& o : order) goals.push_back(o.second);
  rot.prefetch(goals);
}

}  // namespace

PlannerTimes summarize(std::vector<double> ms) { return planner::Latency::of(std::move(ms)); }

LifelongResult run_lifelong(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                            const std::string& solver, uint64_t seed, const LifelongOptions& opt)
{
  LifelongResult r;
  r.action_model = opt.action_model;
  r.starts = starts;
  const bool rotation = opt.action_model == ActionModel::Rotation;
  // pibt-rot plans the robots' actions itself: no cell plan, no RotationExecutor.
  const bool native = is_rotation_native(solver);
  if (native && !rotation)
    throw std::invalid_argument("solver " + solver + " plans rotation actions: it needs --action-model rotation");
  const bool prefetch = opt.prefetch && !native;  // the prefetch grows cell tables, which pibt-rot does not read
  const bool letters = opt.record_actions && g.is_grid();
  if (letters) r.actions.assign(starts.size(), std::string());
  const auto wall0 = Clock::now();
  auto t0 = Clock::now();
  // One distance cache for the task layer, the heading preference and the planner.
  auto cache = std::make_shared<planner::DistCache>(g, opt.max_dist_tables ? opt.max_dist_tables : 2 * starts.size() + 256);
  tasks.share_dist_cache(cache);
  tasks.start(starts);
  // Rotation: PIBT breaks distance ties by the turns a move needs (unless a policy orders moves).
  std::unique_ptr<HeadingPreference> heading;
  planner::ActionPreference* pref = opt.pref;
  if (rotation && !native && !pref && opt.heading_ties) {
    heading = std::make_unique<HeadingPreference>(g, starts, opt.heading_cost);
    heading->share_dist_cache(cache);
    pref = heading.get();
  }
  auto p = make_planner(solver, g, starts, tasks.goals(), lifelong_goal_test(tasks, starts), seed, pref, opt.keep_priorities, opt.refine);
  p->share_dist_cache(cache);
  auto* rot = dynamic_cast<planner::RotationPlanner*>(p.get());  // pibt-rot, epibt, wppl
  if (rot) rot->set_back_last(opt.rot_back_last);
  if (rot && !opt.guidance.uniform()) rot->set_guidance(opt.guidance);
  if (auto* ep = dynamic_cast<planner::Epibt*>(p.get())) {
    planner::EpibtOptions o = opt.epibt;
    o.seed = seed;
    ep->set_options(o);
  }
  if (auto* w = dynamic_cast<planner::Wppl*>(p.get())) w->set_options(opt.wppl);
  if (prefetch) {
    // Preprocessing (LoRR allows it before the first step): the first goals' tables reach
    // the agents, the next goals' reach the first. Later wants are met in the steps' spare time.
    std::vector<planner::DistCache::Want> first;
    for (size_t i = 0; i < starts.size(); ++i) first.push_back({tasks.goals()[i], starts[i]});
    cache->prefetch(first);
    cache->precompute(planner::Clock::time_point::max());
    prefetch_upcoming(tasks, p->current(), *cache);
    cache->precompute(planner::Clock::time_point::max());
  }
  const bool rot_prefetch = rot && opt.prefetch;
  if (rot_prefetch) {  // preprocessing: the next goals' tables (the first ones grew in set_goals)
    prefetch_rotation(tasks, *rot);
    rot->precompute(planner::Clock::time_point::max());
  }
  // The prefetch queue this run uses (cell tables, or pibt-rot's own).
  // Work for the steps' spare time: the cell tables' queue (prefetched goals and tables that
  // bounded queries estimated, with or without prefetch) and pibt-rot's own tables.
  // pibt-rot's queue also holds the tables its bounded queries met (late), prefetch or not.
  auto pending = [&] { return cache->pending() + (rot ? rot->pending() : 0); };
  auto precompute = [&](planner::Clock::time_point deadline) {
    cache->precompute(deadline);
    if (rot) rot->precompute(deadline);
  };
  std::unique_ptr<RotationExecutor> exec;
  if (rotation && !native) exec = std::make_unique<RotationExecutor>(g, starts, opt.rotation_window);
  r.setup_ms = ms_since(t0);
  r.epochs = 1;

  double carry_ms = 0;  // set_goals at the end of the last step: planning for this one
  double carry_cpu_ms = 0;
  uint64_t carry_pops = 0;
  // CPU ms of one search expansion (cost_estimate.hpp): an expansion cannot stop halfway,
  // so each is charged its bound before it starts. The step's first one (at the root: PIBT
  // with the heading preference, on tables just created) costs up to twice the later ones.
  CostEstimate first, later;
  // One deadline for all of a step's planning: queries past it answer lower bounds instead
  // of growing tables (dist_cache.hpp). Off (bound_queries false, or no positive time
  // budget: a 0 ms budget means one expansion per step in tests): every query exact.
  const bool bounded = opt.bound_queries && opt.budget.ms > 0 && opt.budget.ms < 1e12;
  auto bound_queries = [&](planner::DistCache::Deadline d) {
    if (bounded) cache->set_deadline(d);
    if (bounded && rot) rot->set_deadline(d);  // pibt-rot's (cell, heading) tables likewise
  };
  // RT-LaCAM may make no expansion in a step: the agents follow the tree or wait.
  const auto* rt = dynamic_cast<const planner::RtLacam*>(p.get());
  const bool may_skip = opt.skip_late_search && bounded && rt;
  // How far (ms) the step's last table growth runs past its deadline (a BFS chunk, a page
  // fault): the step ends that much early.
  CostEstimate overrun;
  int skipped = 0;  // searches skipped in a row
  for (long t = 1; t <= opt.steps; ++t) {
    if (planner::stop_signal()) break;  // SIGINT / SIGTERM: end here, the caller writes the log
    StepRecord rec;
    rec.t = t;
    rec.epoch = r.epochs;
    planner::Budget b = opt.budget;
    const double guard = bounded ? overrun.bound(opt.expansion_deviations) : 0.0;
    b.ms = std::max(0.0, b.ms - carry_ms - guard);  // the epoch start is inside the step's budget
    t0 = Clock::now();
    const double cpu0 = thread_cpu_ms();
    const uint64_t pops0 = cache->counters().query_pops;
    const auto step_end = b.deadline_from(t0);
    bound_queries(step_end);
    const double reserve = first.bound(opt.expansion_deviations);
    bool plan_now = !exec || exec->can_accept();
    if (!plan_now) ++r.window_full;
    // No room left for one expansion (the epoch start took it): no search this step. Only
    // when a step without an epoch start has room for one, and at most kMaxSkips in a row:
    // the search keeps making progress (and its cost estimate fresh) whatever the budget.
    const bool skip = plan_now && may_skip && skipped < kMaxSkips && first.known() && b.ms < reserve &&
                      opt.budget.ms >= reserve;
    skipped = skip ? skipped + 1 : plan_now ? 0 : skipped;
    const bool search_now = plan_now && !skip;
    if (skip) {
      ++r.searches_skipped;
      if (exec) plan_now = false;  // the robots run their window; a wait would take a slot of it
    }
    if (search_now && pending() > 0) {
      // Tables first, up to the share: an expansion that meets an incomplete table would pay
      // its BFS anyway, all at once.
      // It leaves room for the one expansion the search always makes.
      // It overruns its deadline too (guard).
      const double share = std::min(opt.precompute_share * b.ms, b.ms - reserve) - guard;
      precompute(planner::Budget::time_ms(std::max(0.0, share)).deadline_from(t0));
      rec.precompute_ms = ms_since(t0);
      b.ms = std::max(0.0, b.ms - rec.precompute_ms);
    }
    planner::Config next;
    if (search_now) {
      const auto t1 = Clock::now();
      double c1 = thread_cpu_ms();
      // Rotation-native planners (pibt-rot, epibt, wppl) plan a whole step in one call and
      // check the deadline themselves: give them the time left (an expansion-count call
      // would run them without a clock).
      if (!bounded || rot) {  // no time limit (or exact queries): the search's own loop, as before
        b.ms = std::max(0.0, b.ms - reserve);  // it checks its deadline after each expansion
        if (bounded) bound_queries(b.deadline_from(t1));
        const uint64_t e0 = p->expansions();
        p->search(b);
        if (const uint64_t de = p->expansions() - e0; de > 0)
          first.add((thread_cpu_ms() - c1) / static_cast<double>(de));
      } else {
        // The first expansion always (the skip above decided), measured alone; then the
        // search goes on while one more expansion's bound fits before the deadline
        // (Budget::reserve_ms). Queries stop growing tables where the first expansion's
        // bound begins, as the search's own deadline did.
        const auto end = b.deadline_from(t1);
        bound_queries(planner::Budget::time_ms(std::max(0.0, b.ms - reserve)).deadline_from(t1));
        uint64_t e0 = p->expansions();
        p->search(planner::Budget::expansion_count(1));
        double c = thread_cpu_ms();
        if (p->expansions() > e0) first.add(c - c1);
        const CostEstimate& est = later.known() ? later : first;
        const double left = std::chrono::duration<double, std::milli>(end - Clock::now()).count();
        if (b.expansions > 1 && p->expansions() > e0 && left > est.bound(opt.expansion_deviations)) {
          e0 = p->expansions();
          c1 = c;
          p->search({left, b.expansions - 1, est.bound(opt.expansion_deviations)});
          c = thread_cpu_ms();
          // The call's costliest expansion where the search tells it (RT-LaCAM), else the mean:
          // expansions that revisit a known configuration are cheap, new nodes are not.
          if (const uint64_t de = p->expansions() - e0; de > 0)
            later.add(rt ? rt->max_expansion_ms() : (c - c1) / static_cast<double>(de));
        }
      }
      next = p->next();
    } else if (plan_now) {
      next = p->next();
    }
    if (pending() > 0 && Clock::now() < step_end) {
      const auto t1 = Clock::now();  // time left: the search ended early or the window is full
      precompute(step_end);
      rec.precompute_ms += ms_since(t1);
      // How far it ran past the deadline, when the deadline stopped it (not when it ran out
      // of work); a sample above a tenth of the budget is preemption, not work.
      if (pending() > 0) overrun.add(std::clamp(ms_since(step_end), 0.0, 0.1 * opt.budget.ms));
    }
    rec.planner_ms = ms_since(t0) + carry_ms;
    rec.planner_cpu_ms = thread_cpu_ms() - cpu0 + carry_cpu_ms;
    rec.query_pops = cache->counters().query_pops - pops0 + carry_pops;
    rec.epoch_start_ms = carry_ms;
    rec.epoch_start_cpu_ms = carry_cpu_ms;
    if (rec.planner_ms > opt.budget.ms + 0.05) ++r.steps_over_budget;
    if (rec.planner_cpu_ms > opt.budget.ms + 0.05) ++r.steps_over_budget_cpu;
    rec.explored = p->explored();
    bound_queries(planner::DistCache::Deadline::max());  // the task layer's queries: exact, as before

    if (plan_now) {
      const std::string err = planner::Validator::check_transition(g, p->current(), next);
      if (!err.empty() && r.planner_errors++ == 0) {
        r.first_error = "step " + std::to_string(t) + ": " + err;
        r.first_error_t = t;
      }
      if (letters && !rotation)
        for (size_t i = 0; i < next.size(); ++i) r.actions[i] += grid4_letter(g, p->current()[i], next[i]);
      if (rot) {  // the actions themselves: forward into the cell ahead, turns and waits in place
        const std::string bad = check_rotation_step(g, p->current(), rot->headings(), rot->actions(), next);
        if (!bad.empty() && r.planner_errors++ == 0) {
          r.first_error = "step " + std::to_string(t) + ": " + bad;
          r.first_error_t = t;
        }
        if (letters)
          for (size_t i = 0; i < next.size(); ++i) r.actions[i] += rot->actions()[i];
      }
      p->commit();
      if (heading) heading->committed(p->current());
    }
    const planner::Config* real = &p->current();
    if (exec) {
      if (plan_now) exec->push(p->current());
      const planner::Config before = exec->positions();
      const std::string& act = exec->step();
      // The executed step is checked like a planned one: cells, adjacency, vertex and swap conflicts.
      const std::string err = planner::Validator::check_transition(g, before, exec->positions());
      if (!err.empty() && r.planner_errors++ == 0) {
        r.first_error = "step " + std::to_string(t) + " (executed): " + err;
        r.first_error_t = t;
      }
      if (letters)
        for (size_t i = 0; i < act.size(); ++i) r.actions[i] += act[i];
      real = &exec->positions();
    }

    // advance_epoch, split to time the task layer apart from the planner. Errands complete
    // on the robots' real cells; the planner's new epoch starts at its own current
    // configuration (the plan frontier under rotation).
    t0 = Clock::now();
    const std::vector<Event> ev = tasks.update(t, *real);
    r.task_ms += ms_since(t0);
    t0 = Clock::now();
    const double carry_cpu0 = thread_cpu_ms();
    const uint64_t carry_pops0 = cache->counters().query_pops;
    // Rotation: the plan frontier runs ahead of the robots, so it can reach a goal before
    // the robot does. Its epoch's goal test then holds and RT-LaCAM would only wait; a new
    // epoch at the frontier (that agent no longer pending) keeps the others' plans going.
    // The robot still completes the errand when it physically gets there.
    const bool replan = !ev.empty() || (exec && plan_now && p->at_goal() && has_pending(tasks, p->current()));
    // The epoch start is the next step's planning: its table growth stops at the share of
    // that step's budget the precompute may take, less the one expansion the search will
    // make (at 1 ms on WAREHOUSE, none: the next step's precompute grows what it missed).
    bound_queries(planner::Budget::time_ms(std::max(0.0, opt.precompute_share * opt.budget.ms - first.bound(opt.expansion_deviations)))
                      .deadline_from(t0));
    if (replan) p->set_goals(tasks.goals(), lifelong_goal_test(tasks, p->current()));
    if (!ev.empty() && prefetch) prefetch_upcoming(tasks, p->current(), *cache);
    if (!ev.empty() && rot_prefetch) prefetch_rotation(tasks, *rot);
    carry_ms = replan ? ms_since(t0) : 0.0;
    carry_cpu_ms = replan ? thread_cpu_ms() - carry_cpu0 : 0.0;
    carry_pops = replan ? cache->counters().query_pops - carry_pops0 : 0;
    if (replan) ++r.epochs;
    rec.completed = static_cast<int>(ev.size());
    rec.new_epoch = !ev.empty();
    r.events.insert(r.events.end(), ev.begin(), ev.end());
    r.planner_ms.push_back(rec.planner_ms);
    r.planner_cpu_ms.push_back(rec.planner_cpu_ms);
    r.query_pops_max = std::max(r.query_pops_max, rec.query_pops);
    r.epoch_start_ms.push_back(rec.epoch_start_ms);
    r.epoch_start_cpu_ms.push_back(rec.epoch_start_cpu_ms);
    r.precompute_ms.push_back(rec.precompute_ms);
    // pibt-rot: its (cell, heading) tables count beside the task layer's cell tables.
    const size_t rot_tables = rot ? rot->dist().num_tables() : 0;
    r.dist_tables_max = std::max(r.dist_tables_max, cache->num_tables() + rot_tables);
    if (t % 16 == 0 || t == opt.steps)
      r.dist_mb_max = std::max(r.dist_mb_max, static_cast<double>(cache->bytes() + (rot ? rot->dist().bytes() : 0)) / (1 << 20));
    r.steps = t;
    if (opt.on_step) opt.on_step(rec);
  }
  cache->set_deadline(planner::DistCache::Deadline::max());  // the task layer keeps the cache: exact again
  if (exec) r.final_headings = exec->headings();
  if (rot) r.final_headings = rot->headings();
  r.dist_tables = cache->num_tables() + (rot ? rot->dist().num_tables() : 0);
  r.dist_counters = cache->counters();
  r.ms_per_expansion = later.known() ? later.mean : first.mean;
  r.ms_per_first_expansion = first.mean;
  r.errands_finished = tasks.errands_finished();
  r.tasks_finished = tasks.tasks_finished();
  r.expansions = p->expansions();
  r.wall_ms = ms_since(wall0);
  return r;
}

}  // namespace tasks
