#pragma once
// Run: one Controller::run() split into its phases (private to controller/):
//   prepare()        everything that can be wrong with the input -> ConfigError, before SUMO
//   start_sumo()     back end, vType, insertion, start poses checked
//   loop_lockstep()  run.executor: lockstep -- all AGVs one configuration per tick (scheme S)
//   loop_adg()       run.executor: adg -- the ADG releases moves, AGVs drive physically
//   finish()         metrics.json, the lifelong log, plan.txt
// step() is the one SUMO step both loops share: planner slice, SUMO, event and safety checks.
// Lifelong (tasks.mode: lifelong): the task and epoch phases are the grid's, through
// tasks::LifelongEpochs (tasks/lifelong_epochs.hpp): start, completions on the executed
// cells, the epoch start, the counts; and the SUMO step's budget is the grid's object
// (tasks::StepBudget, sb_); what happens around them stays here (rules' goals, the
// validator, goal markers).
#include <algorithm>
#include <memory>
#include <optional>

#include "controller/bound.hpp"
#include "controller/commander.hpp"
#include "controller/congestion.hpp"
#include "controller/controller.hpp"
#include "controller/driver.hpp"
#include "controller/fleet_view.hpp"
#include "controller/rule_check.hpp"
#include "controller/rules.hpp"
#include "controller/safety.hpp"
#include "stuck_replan.hpp"
#include "executor/adg.hpp"
#include "executor/delay_model.hpp"
#include "executor/out_and_back.hpp"
#include "planner/dist_cache.hpp"
#include "planner/instance.hpp"
#include "planner/stop_signal.hpp"
#include "planner/validator.hpp"
#include "policy/policy_preference.hpp"
#include "tasks/lifelong_epochs.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/queue_trace.hpp"
#include "tasks/step_budget.hpp"
#include "tasks/task_manager.hpp"

namespace controller {

class Run {
 public:
  Run(const Config& cfg, Controller& c) : cfg_(cfg), c_(c) {}
  Metrics execute();

 private:
  void prepare();
  void start_sumo();
  void loop_lockstep();
  void loop_adg();
  void finish();
  // Every end of a run (goals, tick limit, error, abort): each AGV in SUMO is brought to
  // rest before the controller detaches -- at its vType's decel (adg executors), or at once
  // (lockstep: scheme S stops every AGV in one step) -- so a SUMO that outlives the
  // controller has no AGV driving on.
  void stop_all();

  // One SUMO step: a planner slice first (timed), then SUMO, its events, and Safety with
  // the cells each AGV may occupy now.
  void step(const std::vector<std::vector<planner::Vertex>>& allowed, bool exclusive, const std::vector<int>& groups = {});
  std::vector<VehiclePose> poses();
  // The budget of a search that plans a step: budget_, a tick's worth for a rotation solver.
  planner::Budget plan_budget() const;
  planner::Budget startup_budget() const;  // the search before the first command (planner.startup_ticks)
  // Lifelong: thousands of goal cells over a run; p_ keeps the distance tables in use plus a
  // few hundred recent ones.
  void cap_dist_tables()
  {
    if (tm_) p_->set_max_dist_tables(2 * ins_.starts.size() + 256);
  }
  // One-shot: the instance bounds of metrics.json (instance_bound.hpp), before the run.
  void instance_bound();
  Kinematics kinematics() const  // the vType's, for the physical bounds (bound.hpp)
  {
    return {cfg_.fleet.vtype.accel, cfg_.fleet.vtype.decel, cfg_.fleet.vtype.max_speed, cfg_.sumo.step_length};
  }
  // Lifelong: completions at the end of tick `t` against the executed positions.
  void lifelong_tick(const planner::Config& executed, double tick_planner_ms);
  // The epoch start of the tick that ends at `tick` (task layer, new goals): lifelong_tick
  // calls it at the tick's end, lockstep at its start (epoch_early).
  void epoch_start(const planner::Config& executed, long tick);
  bool epoch_early() const;
  // An epoch's new goals (set_goals with the lifelong goal test) at `t0`, their distance reads
  // within the step's budget when bounded (run.epoch_in_budget and a time budget): returns
  // whether it was, and then the cache's deadline stays set for the caller to lift.
  bool epoch_goals(const planner::Config& goals, planner::Clock::time_point t0);
  // Plan completions (run.plan_completions; adg, lifelong): the task layer runs on the
  // committed plan. Without them an errand was completed only once its AGV had driven
  // there, and until then the epoch's goal test ("some awaited agent on its goal") held
  // every commit: the whole fleet's plan waited for the one AGV, up to run.window steps
  // behind the frontier (huge warehouse, 1000 AGVs: one plan step per 1.7 ticks). Now each
  // committed configuration goes to the task layer (one task step each): an errand is done
  // for planning when a commit puts its AGV on the errand's cell, the next goal is planned
  // at once, as in lockstep, and the errand is counted (events, throughput) at the tick
  // the AGV has executed that configuration (Adg::progress). Its cell stays an
  // out-and-back keep until then, so the visit is never cut. A stuck replan cuts the
  // committed window: an errand it cuts off before the AGV got there becomes a debt, the
  // AGV's planner goal until a commit puts it there again (the task layer then sees the AGV
  // on the debt's cell, so its later errands wait). Off (the executed cells, as before)
  // with batteries, rules and rotation solvers.
  struct PlanCompletion {
    tasks::Event ev;
    long long step = 0;  // ADG configuration that puts the AGV on the errand's cell
    bool task_done = false;
    planner::Vertex cell = -1;
  };
  bool plan_mode() const;
  // After a commit: configuration `c` is the ADG's configuration `step` (after the lookahead).
  void plan_update(const planner::Config& c, long long step);
  void release_completions(const executor::Adg& adg);  // tick end: what the AGVs executed
  // A replan: `prog` each AGV's progress in the old ADG, `steps` the new ADG's first
  // configurations; completions it cuts off become debts.
  void plan_debts(const std::vector<long long>& prog, const std::vector<planner::Config>& steps);
  planner::Config plan_goals() const;                 // the task layer's goals, debts first
  std::vector<PlanCompletion> pending_;
  std::vector<std::vector<PlanCompletion>> debts_;
  long task_clock_ = 0;
  bool plan_moved_ = false;  // a commit since the last tick end
  long long plan_errands_ = 0, plan_tasks_ = 0;  // executed
  // Lifelong, planner.prefetch: the goals to come into the planner's distance tables
  // (tasks::LifelongEpochs::prefetch), grown at once when `now` (before the run, as the
  // grid's preprocessing), else in the SUMO steps' spare budget (step(), and the rotation
  // solvers' slices). Cell tables only while the planner uses dist_cache_ (not on a rules
  // graph, whose planner has tables of its own).
  void prefetch_goals(bool now);
  // step(), cell solvers with a time budget: the prefetched tables first, up to the grid's
  // share of the step's budget `b` less one expansion (StepBudget::precompute_ms); returns
  // the time it took.
  double precompute_first(const planner::Budget& b, planner::Clock::time_point t0);
  bool cell_prefetch() const { return prefetch_ && dist_cache_ && !rules_graph_; }
  // Lifelong with fleet.battery: the battery metrics, a warning for each AGV run empty.
  void count_battery(const tasks::Battery& b);
  void progress_line(const planner::Config& executed);
  // adg, after each SUMO step: the stuck-AGV watch (stuck_replan.hpp) and, when the set
  // of immobile AGVs changes, replan(): new planner and ADG from where the AGVs are and are
  // driving to, `immobile` AGVs kept in place.
  void stuck_step(executor::Adg& adg, Driver& drv);
  // regraph: the rules' graph changed (a closure began or ended, a zone is routed around or
  // free again): the planner is rebuilt on the new one, from the same place.
  void replan(executor::Adg& adg, Driver& drv, const std::vector<uint8_t>& immobile, bool regraph = false);
  // Traffic rules under adg, at a tick boundary: closures that began or ended and zones
  // whose blocking changed replan() from the observed state on the new rules graph.
  void rules_tick_adg(executor::Adg& adg, Driver& drv);
  // Configurations before C^t are final (ExecutedPlan::settle); with stuck replans the
  // validator of the final prefix steps over them first (a replan re-validates from there).
  void settle(size_t t);
  // What a person sees (run_view.cpp): each AGV's state colour once its commands are out
  // (lockstep: per tick from the step it executes; adg: before every SUMO step, from the
  // ADG after the Driver's starts), goal markers when goals change, the congestion counts
  // per tick and their picture.
  void show_lockstep(const planner::Config& cur, const planner::Config& next, bool held);
  void show_adg(const executor::Adg& adg);
  void show_goals();
  bool carrying(int i) const;  // lifelong: its task's pick-up done, on its way to deliver
  const planner::Config& goals() const { return tm_ ? tm_->goals() : ins_.goals; }
  void count_tick(const planner::Config& executed, int ticks = 1);
  // Traffic rules (rules.hpp), lockstep: at a tick boundary, closures that began or ended
  // and zones that filled or emptied restart the planner at `cur` on the rules' graph;
  // rules_restart() builds that planner (goals it cannot reach: the AGV waits);
  // rule_goals() the goals the planner gets from `at` on a rules graph `g` (the current one,
  // or the one rules_restart() is about to plan on), logging the AGVs that must wait.
  void rules_tick(const planner::Config& cur);
  // Polls the rules; on a closure change: SUMO avoids the closed edges, counters, one line,
  // closure_tasks(). Returns whether the closures changed.
  bool rules_update();
  void rules_restart(const planner::Config& at);
  // Lifelong: the net without the arcs into closed cells, for the task layer (an errand a
  // closure cuts off goes back to the pool: tasks/task_manager.hpp).
  void closure_tasks();
  planner::Config rule_goals(const planner::Graph& g, const planner::Config& at);
  void write_congestion();
  // The tick limit, a SIGINT / SIGTERM (planner/stop_signal.hpp), or a one-shot instance the
  // search proved unsolvable (RT-LaCAM's DFS exhausted: waiting for max_ticks would change
  // nothing): each ends the loop through its normal end, so finish() writes every output
  // and closes SUMO.
  bool out_of_ticks() const
  {
    return m_.ticks >= cfg_.run.max_ticks || planner::stop_signal() != 0 || proven_unsolvable();
  }
  // One-shot: the search proved no solution on the real graph (not on one the rules narrowed
  // for a while: closures end, zones empty).
  bool proven_unsolvable() const
  {
    if (tm_ || !p_ || !p_->exhausted()) return false;
    return !rules_ || (!rules_->anything_closed() && std::find(zone_occ_.begin(), zone_occ_.end(), 1) == zone_occ_.end());
  }

  const Config& cfg_;
  Controller& c_;
  Metrics m_;
  planner::Instance ins_;
  // The graph as driven (lane costs only) for the free-flow bound, while tasks.urgency.
  // mouth_cost adds routing costs to the planner's (declared before tm_: it outlives it).
  std::unique_ptr<planner::Graph> drive_graph_;
  std::unique_ptr<tasks::TaskManager> tm_;
  policy::Model model_;
  std::unique_ptr<policy::PolicyPreference> pref_;
  std::string dir_;
  double max_spacing_ = 0;
  std::unique_ptr<SumoBackend> sumo_;
  std::unique_ptr<Commander> cmd_;
  std::unique_ptr<Safety> safety_;
  std::unique_ptr<Rules> rules_;
  std::unique_ptr<RuleCheck> rule_check_;
  // The planner's graph while rules_ exist (declared before p_: it outlives the planner).
  std::unique_ptr<planner::Graph> rules_graph_;
  std::shared_ptr<const planner::Zones> plan_zones_;  // rules.plan_zones: the planner keeps the zones
  std::vector<uint8_t> zone_occ_, waiting_;  // zones the planner's graph blocks; agents waiting
  std::unique_ptr<planner::Graph> open_graph_;  // closure_tasks(); null while nothing is closed
  std::unique_ptr<planner::RealtimePlanner> p_;
  std::unique_ptr<planner::Validator> val_;
  // Stuck replans: the validator at the last final configuration C^val_final_at_ (a replan
  // copies it and checks only the rewritten steps), and the cell solvers' distance tables,
  // kept from one planner to the next (a fresh planner would redo a BFS per AGV).
  std::optional<planner::Validator> val_final_;
  size_t val_final_at_ = 0;
  std::shared_ptr<planner::DistCache> dist_cache_;
  std::unique_ptr<executor::DelayModel> delays_;
  std::unique_ptr<StuckWatch> stuck_;  // run.replan_on_stuck (adg)
  // adg, one-shot cell plans: the commits held back to cut out-and-backs (run.out_and_back);
  // a replan drops what it holds.
  std::unique_ptr<executor::OutAndBack> oab_;
  std::unique_ptr<FleetView> view_;
  std::unique_ptr<Congestion> congestion_;
  std::vector<AgvState> states_;
  uint64_t replan_expansions_ = 0;     // expansions of the planners replaced by replans
  tasks::LifelongResult life_;
  // Lifelong: the task and epoch part shared with the grid's LifelongRun (start,
  // completions on the executed cells, epoch starts, their counts in life_).
  std::unique_ptr<tasks::LifelongEpochs> epochs_;
  std::unique_ptr<tasks::QueueTrace> queue_trace_;  // output.queue_trace
  bool prefetch_ = false;  // lifelong and planner.prefetch
  planner::Budget budget_;
  int k_ = 1;
  int slice_ = 0;  // SUMO step within the tick (lockstep), for the rotation solvers' budget
  // Bounded however long the run (lifelong): exact up to 16384 samples, a reservoir beyond.
  planner::LatencySample plan_step_, plan_tick_, sumo_step_, control_, exec_step_;
  double plan_in_tick_ = 0, epoch_ms_ = 0;
  // Planner work on this thread's CPU per SUMO step (search, commits, epoch starts, replans):
  // what planner.budget_ms bounds, told apart from time the thread was preempted.
  planner::LatencySample plan_cpu_step_;
  // The SUMO step's planning budget, the grid's object (tasks/step_budget.hpp): the carry
  // (thread CPU of the commits, replans, rules restarts and epoch starts since the last
  // step's search), the guard, one expansion's reserve, the precompute share, skipped searches.
  tasks::StepBudget sb_{planner::Budget{}, 4, 0.5, false};
  std::vector<VehiclePose> last_poses_;
  // The physical bound over the executed plan's configurations that left memory (all of
  // them at the end): bound.hpp.
  std::optional<AloneBound> alone_;
  std::vector<int> start_headings_;  // rotation solvers: each AGV's heading at its start
  planner::Clock::time_point wall0_, loop0_, last_progress_;
};

}  // namespace controller
