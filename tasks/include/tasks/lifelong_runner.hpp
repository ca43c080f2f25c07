#pragma once
// The lifelong run on the plain MAPF graph: its options, its step record and its result;
// run_lifelong runs a LifelongRun (lifelong_run.hpp: the phases, StepBudget) to the end.
// Each step:
//
//   search(budget); next()        -- plan (timed: plannerTimes)
//   check the move (Validator)    -- any violation counts in numPlannerErrors
//   commit()                      -- the agents are there
//   complete, start_epoch         -- errands completed? then new goals, new epoch
//                                    (LifelongEpochs, lifelong_epochs.hpp: every back end's seam)
//
// Progress epochs: goals change only when an errand completes. RT-LaCAM then restarts its
// tree at the current configuration (set_goals); while nothing completes it keeps its tree,
// explored table and constraints, which is what makes it escape deadlocks and livelocks
// that PIBT and the naive variant fall into.
//
// Rotation (LoRR MAPF_T): the planner still plans cell moves; each step it commits one
// configuration when the RotationExecution's window has room, and the executor turns the
// committed moves into F/R/C/W actions (see executor/rotation_execution.hpp). Errands complete on the
// robots' real cells; the new goals go to the planner at its plan frontier.
//
// Budget: the set_goals that starts an epoch is planning work for the next step; it is
// counted in that step's time and taken out of its search budget (at least one expansion
// still runs), so a step's planner time is the budget unless set_goals alone exceeds it.
// Distance tables: planner, heading preference and pool assigner share one DistCache. The
// goals the task layer knows are coming (TaskManager::upcoming) are prefetched: the first
// goals' tables and the next goals' are grown before step 1 (preprocessing); later, while
// any prefetched table is not yet grown as far as it will be queried, up to
// precompute_share of each step's budget grows it first, and the search gets the rest
// (also whole steps in which the rotation window is full). The search is stopped one
// average expansion before its deadline, since it checks the deadline only between
// expansions. All of a step's planning (the epoch start, precompute, search, the heading
// preference) runs under one deadline on the shared cache (bound_queries): a distance query
// past it gets a lower bound and never grows a table there; the epoch start's growth stops at
// precompute_share of the budget. Numbers: docs/rotation_lorr.md "Planning time at epoch starts".
#include <functional>
#include <string>
#include <vector>

#include "planner/budget.hpp"
#include "planner/dist_cache.hpp"
#include "executor/delay_model.hpp"
#include "executor/graph_execution.hpp"
#include "planner/graph.hpp"
#include "planner/latency.hpp"
#include "planner/realtime_planner.hpp"
#include "planner/solver.hpp"
#include "tasks/action_model.hpp"
#include "tasks/heading_preference.hpp"
#include "tasks/task_manager.hpp"

namespace tasks {

struct StepRecord {      // what one step did (for tests and progress output)
  long t = 0;
  double planner_ms = 0;
  double epoch_start_ms = 0;  // the set_goals that started this step's epoch (in planner_ms)
  double epoch_start_cpu_ms = 0;  // its thread CPU time
  double precompute_ms = 0;   // growing prefetched distance tables (in planner_ms)
  double planner_cpu_ms = 0;  // this thread's CPU time over the same work (planner_ms minus preemption)
  uint64_t query_pops = 0;    // BFS vertices grown inside distance queries (search, set_goals)
  int completed = 0;     // errands completed at the end of this step
  bool new_epoch = false;
  size_t explored = 0;   // planner's explored table after search, before any reset
  long epoch = 0;        // epoch in which the step was planned
};

inline planner::SolverOptions lifelong_solver_defaults()
{
  planner::SolverOptions o;
  o.lacam.refine = true;
  o.lacam.keep_priorities = true;
  return o;
}

struct LifelongOptions {
  long steps = 1000;
  planner::Budget budget = planner::Budget::time_ms(100);
  std::function<void(const StepRecord&)> on_step;  // optional, after every step
  // The solver's options (planner/solver.hpp), given to the factory at construction. The
  // runner sets seed (run_lifelong's), max_dist_tables (the lifelong cap) and, under rotation
  // without a policy in solver.pref, the heading preference. Lifelong defaults: RT-LaCAM*
  // refinement on (lacam.refine), PIBT priorities kept across epochs (lacam.keep_priorities).
  planner::SolverOptions solver = lifelong_solver_defaults();
  ActionModel action_model = ActionModel::Grid4;
  int rotation_window = 8;     // rotation: plan steps the planner may run ahead of the slowest robot
  bool heading_ties = true;    // rotation: HeadingPreference orders PIBT's moves (else plain PIBT)
  HeadingCost heading_cost = HeadingCost::Turns;  // rotation: how (heading_preference.hpp)
  bool record_actions = false; // keep every robot's action letters (LoRR actualPaths)
  bool prefetch = true;          // grow the tables of upcoming goals in spare step time
  double precompute_share = 0.5;   // of a step's budget at most, first, while prefetched tables are incomplete
  size_t max_dist_tables = 0;      // shared cache cap; 0: 2 x agents + 256
  // Distance queries past the step's deadline answer lower bounds instead of growing tables
  // (planner/dist_cache.hpp); false: every query exact, however long its BFS (as before).
  // Only with a positive, finite time budget (expansion-only budgets stay deterministic).
  bool bound_queries = true;
  // With a time budget, the search stops one expansion's cost bound early: mean + this many
  // mean deviations of the recent expansions' CPU time (tasks/cost_estimate.hpp).
  double expansion_deviations = 4;
  // rtlacam with a time budget: a step whose time left (after its epoch start) is below the
  // first expansion's bound makes no expansion (the agents follow the tree or wait; under
  // rotation nothing is pushed) instead of overrunning the budget by one. Off by default: on
  // WAREHOUSE 1,000 agents at 1 ms it changed rotation throughput by -34 to +5 % for no
  // reliably better p99 (docs/rotation_lorr.md "Budget at 1 ms"); false: every step makes
  // at least one.
  bool skip_late_search = false;
  // grid4 under delays (executor/graph_execution.hpp; run_lifelong_exec): the planner
  // searches every step and fills the execution's window with its commits (never a wait);
  // errands complete where the agents really are. Off: every commit is executed at once.
  bool graph_execution = false;
  executor::ExecOptions exec;
  executor::DelaySpec delays;
};

using PlannerTimes = planner::Latency;  // one p99 definition for all layers
PlannerTimes summarize(std::vector<double> ms);

// LifelongEpochs::count()'s results: the task layer's view of congestion at stations.
struct EpochCounts {
  long long max_goal_ticks = 0;  // longest any agent kept one goal, idle ones too (open ones to now)
  int max_heading = 0;           // most busy agents heading for one errand cell at once
  long long queued_ticks = 0;    // agent-steps busy, on their goal, that goal not the errand's cell (a queue)
  long clearings = 0;            // station pockets cleared (tasks.queues.clear_after, jam_after), so far
  long jam_clearings = 0;        // of those, jams cleared (tasks.queues.jam_after)
  long clearing_steps = 0;       // steps stations spent clearing, summed over stations
  int longest_clearing = 0;      // the longest clearing in steps (an open one to now)
  int idle = 0, parked = 0;      // at the last count: agents without a task, those of them on a parking cell
  long long idle_ticks = 0, parked_ticks = 0;  // the same summed over the counts (agent-steps)
};

struct LifelongResult {
  long steps = 0;
  long errands_finished = 0, tasks_finished = 0;
  long epochs = 0;                  // set_goals calls, the initial goals included
  std::vector<Event> events;
  std::vector<double> planner_ms;   // per step: search + next (+ set_goals of its epoch start)
  std::vector<double> epoch_start_ms;  // per step: the set_goals part of planner_ms (0 without a new epoch)
  std::vector<double> precompute_ms;   // per step: the prefetch part of planner_ms
  long steps_over_budget = 0;       // planner_ms above the time budget (+ 0.05 ms of timer slack)
  std::vector<double> planner_cpu_ms;  // per step: thread CPU time of the planner_ms work
  std::vector<double> epoch_start_cpu_ms;  // per step: thread CPU time of the epoch_start_ms work
  double ms_per_expansion = 0;      // the runner's moving average of a search expansion, at the end
  double ms_per_first_expansion = 0;  // the same for a step's first expansion (at the root)
  long steps_over_budget_cpu = 0;   // the same count on CPU time (preemption does not count)
  uint64_t query_pops_max = 0;      // most BFS vertices grown inside queries in one step
  planner::DistCache::Counters dist_counters;  // the shared cache's work counters at the end
  size_t dist_tables = 0, dist_tables_max = 0;  // shared distance cache: at the end, most at once
  double dist_mb_max = 0;           // its memory at its largest (sampled every step)
  double setup_ms = 0;              // first assignment + planner construction
  double task_ms = 0;               // task layer (completions, reveals, assignment) over all steps
  double wall_ms = 0;
  long planner_errors = 0;
  std::string first_error;          // first validator message, "" when clean
  long unreachable_goals = 0;       // at the end: agents whose goal cannot be reached from their cell
  bool unsolvable_epoch = false;    // at the end: the planner proved its epoch's goals unsolvable
  long first_error_t = 0;           // its step
  uint64_t expansions = 0;
  ActionModel action_model = ActionModel::Grid4;
  planner::Config starts;
  std::vector<std::string> actions;  // per robot, one LoRR letter per step (record_actions)
  std::vector<int> final_headings;   // rotation only
  long window_full = 0;              // rotation: steps the planner waited for the slowest robot
  long searches_skipped = 0;         // steps with no room for an expansion (skip_late_search)
  EpochCounts counts;                // at the end (LifelongEpochs::count after every step)
};

// Starts the tasks at `starts`, builds `solver` (planner::make_planner, any name of
// planner::solver_list(true); the rotation solvers need the rotation action model) and runs.
LifelongResult run_lifelong(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks,
                            const std::string& solver, uint64_t seed, const LifelongOptions& opt);

}  // namespace tasks
