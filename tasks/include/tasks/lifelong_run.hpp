#pragma once
// LifelongRun: one lifelong run on the MAPF graph, as named phases (the shape of the SUMO
// controller's controller/src/run.hpp). run_lifelong (lifelong_runner.hpp) is
//
//   LifelongRun run(g, starts, tasks, solver, seed, opt);
//   while (!run.done()) run.step();
//   return run.finish();
//
// and each step() runs the phases in this order:
//
//   open      the step's budget (StepBudget: the epoch start carried in, the guard),
//             distance queries bounded by its deadline; may the planner run (the
//             execution's window), must the search be skipped (skip_late_search)
//   precompute  prefetched tables first, up to a share of the budget
//   plan      search (one expansion alone, then as many as fit) and next()
//   spare     time left: grow prefetched tables up to the deadline
//   commit    check the planned step (Validator; rotation actions), commit it
//   execute   the Execution runs what was committed (rotation: RotationExecution, one
//             configuration a step, waits included, while its window has room; grid4 under
//             delays: GraphExecution, whose window commit fills, waits dropped; the rotation
//             solvers under delays: GraphExecution with executed headings, one planned step
//             a step); the executed step is checked like a planned one (and its executed
//             LoRR actions, with headings)
//   complete  errands done on the robots' real cells; new goals start a new epoch
//             (set_goals, timed as the next step's planning), upcoming goals prefetched
//   record    the step's record and the run's counters
//
// start, complete and the epoch's bookkeeping are LifelongEpochs' (lifelong_epochs.hpp),
// which the SUMO controller's lifelong mode calls too: the task and epoch logic is one, and
// so is the step budget (StepBudget, step_budget.hpp: the controller's Run::step spends each
// SUMO step through it); the execution is each back end's.
//
// The solver comes from the one factory (planner/solver.hpp) with LifelongOptions::solver;
// the runner reads a rotation solver's actions through RealtimePlanner::rotation().
#include <chrono>
#include <memory>
#include <string>

#include "executor/execution.hpp"
#include "planner/dist_cache.hpp"
#include "planner/graph.hpp"
#include "planner/solver.hpp"
#include "planner/stop_signal.hpp"
#include "tasks/heading_preference.hpp"
#include "tasks/lifelong_epochs.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/step_budget.hpp"
#include "tasks/task_manager.hpp"

namespace tasks {

class LifelongRun {
 public:
  // Starts the tasks at `starts` and builds the solver: the setup (LoRR's preprocessing:
  // the first and next goals' tables) is timed as setup_ms.
  LifelongRun(const planner::Graph& g, const planner::Config& starts, TaskManager& tasks, const std::string& solver,
              uint64_t seed, const LifelongOptions& opt);

  // The last step ran, or SIGINT / SIGTERM asked to stop (planner/stop_signal.hpp): the
  // caller then writes what the run has, complete.
  bool done() const { return t_ >= opt_.steps || planner::stop_signal(); }
  const StepRecord& step();  // one step, all phases
  LifelongResult finish();   // the run's result (call once, after the last step)

  const planner::RealtimePlanner& planner() const { return *p_; }
  long long max_gap() const { return epochs_.max_gap(); }  // longest run of steps without a completion
  // GraphExecution's counters (LifelongOptions::graph_execution), else all 0.
  executor::ExecStats exec_stats() const { return graph_ ? graph_->stats() : executor::ExecStats{}; }

 private:
  struct Step {  // what the phases of one step share
    StepRecord rec;
    planner::Budget b;
    planner::Clock::time_point t0, end;
    double cpu0 = 0, reserve = 0;
    uint64_t pops0 = 0;
    bool plan_now = false, search_now = false;
    planner::Config next;
  };

  void open(Step& s);
  void precompute_first(Step& s);
  void plan(Step& s);
  void spare(Step& s);
  void account(Step& s);
  void commit(Step& s);
  const planner::Config& execute(Step& s);
  void complete(Step& s, const planner::Config& real);
  void record(Step& s);

  size_t pending() const;
  void precompute(planner::Clock::time_point deadline);
  void bound_queries(planner::DistCache::Deadline d);
  void error(long t, const std::string& what);

  const planner::Graph& g_;
  TaskManager& tasks_;
  LifelongOptions opt_;
  LifelongResult r_;
  LifelongEpochs epochs_{tasks_, r_};  // the task and epoch part, shared with the SUMO controller
  planner::Solver kind_;
  bool rotation_, native_, prefetch_, letters_, rot_prefetch_ = false, may_skip_ = false;
  planner::Clock::time_point wall0_;
  std::shared_ptr<planner::DistCache> cache_;
  std::unique_ptr<HeadingPreference> heading_;
  std::unique_ptr<planner::RealtimePlanner> p_;
  planner::RotationPlanner* rot_ = nullptr;
  std::unique_ptr<executor::Execution> exec_;
  executor::GraphExecution* graph_ = nullptr;  // exec_, when it fills its window (graph_execution)
  StepBudget sb_;
  long t_ = 0;
  StepRecord last_;
};

}  // namespace tasks
