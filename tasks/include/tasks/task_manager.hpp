#pragma once
// TaskManager: errand bookkeeping shared by the task modes, and the seam every executor
// (the lifelong runner here, the SUMO controller later) talks to:
//
//   tasks.start(starts)                     -- first goals
//   loop:  ...agents move one step...
//          events = tasks.update(t, positions)  -- completions at the end of step t
//          if (!events.empty()) new epoch with tasks.goals()
//
// Each agent's goal is the cell of its next errand, or its own position while it holds no
// task (it then counts as arrived). Goals change only inside start() and update().
// Optional, set before start(): station queues (an agent not admitted at its errand's
// station waits on a queue cell: station_queues.hpp) and parking (an idle agent goes to a
// parking cell: parking.hpp) and a battery (an agent low between tasks goes to charge:
// battery.hpp; while it charges it holds no task and the mode gives it none; one that
// falls below the critical charge mid-task hands the task back first).
//
// Handing a task back (drop_task): the task stays live with its remaining errands and no
// agent (a pool matches it again, from where it stands; a round-robin agent keeps it for
// later). Two causes: a critical charge, and a closure (set_open_graph) that cuts a pool
// agent off its next errand -- the agent then takes a task it can reach and the errand
// waits in the pool for an agent that can, at the latest until the closure ends.
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_cache.hpp"
#include "planner/dist_table.hpp"
#include "tasks/free_flow.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/battery.hpp"
#include "tasks/errand_stalls.hpp"
#include "tasks/urgency.hpp"
#include "tasks/parking.hpp"
#include "tasks/reachability.hpp"
#include "tasks/station_queues.hpp"
#include "tasks/task.hpp"

namespace tasks {

class TaskManager {
 public:
  explicit TaskManager(std::shared_ptr<const TaskFile> file) : file_(std::move(file)) {}
  virtual ~TaskManager() = default;

  virtual std::string mode() const = 0;

  // Gives the agents their first tasks.
  void start(const planner::Config& positions);
  // End of step t: each agent standing on the cell of its next errand completes it. Then
  // the mode hands out new work. Returns the step's completions (agent order). With
  // station queues the queues are also redone in steps without a completion (a way out
  // clears); goals_changed() says whether any goal changed in the last update().
  std::vector<Event> update(long t, const planner::Config& positions);
  bool goals_changed() const { return goals_changed_; }

  const planner::Config& goals() const { return goals_; }
  // Goals that will be needed soon, for prefetching their distance tables: `agent` will
  // head for `goal` after its current errand. Known in advance: the next errand of a task,
  // the next task of a round-robin agent. (A pool task's first errand is not: the assigner
  // grows its table towards the free agents when it prices them.)
  struct Upcoming {
    int agent = 0;
    planner::Vertex goal = -1;
  };
  virtual std::vector<Upcoming> upcoming() const;
  // Distances the mode needs (the pool's assigner) come from `cache`, shared with the planner.
  virtual void share_dist_cache(std::shared_ptr<planner::DistCache> cache) { share_queue_cache(std::move(cache)); }
  // Errand times and stalls (errand_stalls.hpp) on `g`, the agents' graph: before start()
  // (and before share_dist_cache, whose cache it then uses too).
  void watch_stalls(const planner::Graph& g);
  const ErrandStalls* stalls() const { return stalls_.get(); }
  // Escalation (UrgencyOptions::escalate_after, escalation.hpp): the errand agent a holds has
  // gone escalate_after steps without progress while its holder headed for the errand cell
  // (an errand swapped between agents keeps its count; one handed back to the pool starts
  // anew with its next holder); it stays escalated until it completes. Steps on a queue cell (waiting to be admitted) do not count: the station's
  // admission owns that wait.
  // (Read between update()'s completions and its observation too: only while a holds that errand.)
  bool escalated(int agent) const;
  // watch_stalls on: the errand cell whose dead-end pocket (the cell and the corridor that
  // joins it to the net, battery.hpp dead_end_corridor) holds v; -1 elsewhere.
  planner::Vertex pocket(planner::Vertex v) const { return v < static_cast<planner::Vertex>(pocket_.size()) ? pocket_[v] : -1; }
  // watch_stalls on: pocket() of the errand cells at a dead end only (a station in a through
  // aisle is no pocket to keep out of); the planner's foreign-pocket labels (urgency.hpp).
  const std::vector<planner::Vertex>& dead_end_pockets() const { return dead_end_pocket_; }
  // Priority hints for the planner (urgency.hpp): off unless set.
  void set_urgency(UrgencyOptions o) { urgency_ = o; if (stalls_) stalls_->set_sticky(o.sticky); }
  const UrgencyOptions& urgency() const { return urgency_; }
  long now() const { return now_; }  // the step of the last start() / update()
  // stalls()->summary() at the last update.
  ErrandStalls::Summary stall_summary() const { return stalls_ ? stalls_->summary(now_) : ErrandStalls::Summary{}; }
  // Agents that hold a task (and so have a real errand to reach).
  bool busy(int agent) const { return holding_[agent] >= 0; }
  // Busy and heading for its errand's cell (not waiting in a station's queue or parked).
  bool heading(int agent) const { return busy(agent) && goals_[agent] == task_of(agent)->next_cell(); }
  // Agents an epoch's goal test waits for while they are off their goal
  // (lifelong_goal.hpp): the busy ones, and idle ones sent to a parking cell or off a
  // reserved cell (one left standing in a dead-end station would block it); not an idle
  // agent that just stays where it stood. Reaching a queue or parking goal completes
  // nothing, so update() reports it as a change of goals (a new epoch, goals_changed()).
  bool awaited(int agent) const { return busy(agent) || charging(agent) || (parking_ && parking_->sent(agent)); }
  // On a charging errand: heading for its charger or standing on it.
  bool charging(int agent) const { return battery_ && battery_->charging(agent); }

  // Station queues at every errand cell of the task file (options.on()), and parking
  // (cells may be empty: idle agents then only leave reserved cells). Before start().
  void set_queues(const planner::Graph& g, const QueueOptions& options);
  void set_parking(const planner::Graph& g, std::vector<planner::Vertex> cells);
  // The free-flow bound of the errands this manager sees finished (free_flow.hpp). Before start().
  void set_free_flow(std::unique_ptr<FreeFlowBound> b) { free_flow_ = std::move(b); }
  const FreeFlowBound* free_flow() const { return free_flow_.get(); }
  // Per agent, the cell of the errand it holds now, -1 if it holds no task.
  planner::Config open_errands() const;
  // The free-flow bound over the finished errands and the open ones (free_flow.hpp); 0 without one.
  double free_flow_bound() const { return free_flow_ ? free_flow_->errands_per_step(open_errands()) : 0.0; }
  // Batteries and charging errands (battery.hpp). Idle agents then keep off the chargers
  // (parking's reserved-cell rule). Before start().
  void set_battery(const planner::Graph& g, BatteryOptions options, std::vector<Charger> chargers,
                   std::vector<std::pair<double, double>> xy);
  // The same on a grid (rtlacam-lifelong, Python): cell centres at the grid coordinates (1 m
  // apart), a charger on each of `chargers`, `charge_w` watts for 1 s steps, no losses.
  // std::invalid_argument "key: what" (battery_problem's keys, or "chargers" / "charge_w").
  void set_grid_battery(const planner::Graph& g, BatteryOptions options, const std::vector<planner::Vertex>& chargers,
                        double charge_w);
  const Battery* battery() const { return battery_.get(); }
  // Closures at run time (controller/rules.hpp): `open` is the net without the arcs into
  // closed cells, nullptr when nothing is closed; it must outlive its use (until the next
  // call). From the next update() on, a busy agent that cannot reach its next errand on it
  // hands its task back (modes that can match it elsewhere: reassigns_for_closures()), and
  // no agent is given a task whose next errand it cannot reach.
  void set_open_graph(const planner::Graph* open);
  virtual bool reassigns_for_closures() const { return false; }
  long reassigned_for_closure() const { return reassigned_for_closure_; }  // tasks handed back for a closure
  long dropped_for_charge() const { return dropped_for_charge_; }          // tasks handed back at a critical charge
  StationQueues* queues() { return queues_.get(); }
  const StationQueues* queues() const { return queues_.get(); }
  const Parking* parking() const { return parking_.get(); }
  const Task* task_of(int agent) const;  // null when free

  int num_agents() const { return static_cast<int>(goals_.size()); }
  long errands_finished() const { return errands_finished_; }
  long tasks_finished() const { return tasks_finished_; }
  long tasks_assigned() const { return tasks_assigned_; }
  // History for the LoRR log: every task made live (reveal order), every change of an
  // agent's task (time order).
  const std::vector<TaskRecord>& revealed_tasks() const { return revealed_; }
  const std::vector<Assignment>& assignments() const { return assignments_; }
  const TaskFile& file() const { return *file_; }

 protected:
  // A task of the stream by sequence number (line = id mod file size).
  Task make_task(long id) const;
  // Mode hooks. on_start: assign first tasks. on_finished: `agent` just finished `task`
  // (its slot is already cleared). after_step: once per step with completions, after all
  // on_finished calls (e.g. batch assignment).
  virtual void on_start(const planner::Config& positions) = 0;
  virtual void on_finished(int agent, const Task& task) = 0;
  virtual void after_step(const planner::Config& positions) { (void)positions; }
  // `agent` left its charger (battery.hpp): free for work again. after_step() follows in
  // the same update, so a matching mode needs nothing here.
  virtual void on_charged(int agent) { (void)agent; }
  // `agent` handed back the task in slot `s` (drop_task): the pool matches it again in
  // after_step(); a mode that keeps tasks per agent may hold on to it.
  virtual void on_dropped(int agent, int s) { (void)agent, (void)s; }
  // Once per update(), after the goals are set and before the stalls are observed: a mode
  // may exchange tasks between agents whose goals stay the same (TaskPool: stall handover).
  virtual void exchange_tasks(const planner::Config& positions) { (void)positions; }
  // Agents a and b exchange their tasks (both busy), recorded as two assignments.
  void swap_tasks(int a, int b);
  // Can an agent at `from` reach errand cell `to` (always, when nothing is closed)?
  bool can_reach(planner::Vertex from, planner::Vertex to) const { return !reach_ || reach_->reaches(from, to); }
  bool closures() const { return reach_ != nullptr; }  // set_open_graph gave a graph
  // On a charging errand, or low and waiting for a charger to come free (battery.hpp).
  bool needs_charge(int agent) const { return battery_ && (battery_->charging(agent) || battery_->wants(agent)); }
  // Free for a task: holds none and needs no charge.
  bool assignable(int agent) const { return holding_[agent] < 0 && !needs_charge(agent); }
  // Battery on: can `agent` drive `moves` moves (to t's next errand and along the rest) and
  // then still reach a charger from t's last errand (Battery::affords)? True without one.
  bool affords(int agent, int64_t moves, const Task& t) const
  {
    return !battery_ || battery_->affords(agent, moves, t.errands.back());
  }
  // Battery on: the moves an agent at `from` needs for t -- to its next errand and along the
  // rest (shortest paths on the agents' graph); 0 without a battery or where a leg is
  // unreachable (nothing to judge). The modes without distances of their own (round-robin)
  // price their task check with it.
  int64_t task_moves(planner::Vertex from, const Task& t);
  // `agent` could afford none of the tasks it was matched against: it charges first
  // (Battery::charge_first; nothing when it is already charged to target).
  void charge_instead(int agent, planner::Vertex at)
  {
    if (battery_ && battery_->charge_first(agent)) battery_->consider(agent, at);
  }

  // Task storage: slots hold live tasks; holding_[agent] indexes a slot or is -1.
  int add_task(Task t);                // returns its slot
  void give(int agent, int slot);      // assign an unassigned task
  void release(int agent);             // take back an agent's task (it stays live, unassigned)
  void drop_task(int agent);           // release() for good (the agent gave it up): on_dropped()
  Task& slot(int s) { return slots_[s]; }
  const Task& slot(int s) const { return slots_[s]; }
  void drop(int s);                    // remove a finished task
  std::vector<int> live_slots() const; // slots in use, ascending task id

  void share_queue_cache(std::shared_ptr<planner::DistCache> cache)
  {
    if (stalls_) stalls_->share(cache);
    if (queues_) queues_->share_dist_cache(std::move(cache));
  }

  std::shared_ptr<const TaskFile> file_;
  std::vector<int> holding_;

 private:
  std::unique_ptr<StationQueues> queues_;
  std::unique_ptr<Parking> parking_;
  std::unique_ptr<FreeFlowBound> free_flow_;
  std::unique_ptr<Battery> battery_;
  std::unique_ptr<planner::DistTable> task_dist_;  // set_battery: task_moves()
  std::unique_ptr<Reachability> reach_;  // set_open_graph; null: nothing closed
  std::unique_ptr<ErrandStalls> stalls_;  // watch_stalls
  std::vector<planner::Vertex> pocket_;   // watch_stalls: pocket()
  std::vector<planner::Vertex> evict_;    // escalation: an idle agent's way out of a pocket, -1
  struct Escalation {  // per held task, its open errand's escalation (escalation.hpp)
    int errand = -1;
    long mark = -1;         // the errand's last progress mark seen
    long heading_stall = 0; // steps since it in which its holder headed for the cell
    bool on = false;
    long seen = -1;         // the last step an agent held it
  };
  std::unordered_map<long, Escalation> escalation_;  // task id -> its errand's
  void observe_escalation();
  void evict(const planner::Config& positions);  // escalation.hpp: idle agents out of escalated pockets
  std::vector<planner::Vertex> dead_end_pocket_;  // watch_stalls: dead_end_pockets()
  void observe_stalls(const planner::Config& positions);
  bool rematch_ = false;                 // the open graph changed: match free agents again
  long reassigned_for_closure_ = 0, dropped_for_charge_ = 0;
  // Hands back the tasks of agents critically low or cut off by a closure; true if any.
  bool hand_back(const planner::Config& positions);
  std::vector<uint8_t> reserved_;  // queues' reserved cells, the chargers and the stations (battery on)
  std::vector<uint8_t> station_cells_;  // battery on: errand cells and their dead-end corridors
  // Sends agents without a task that are low to charge; true if any went.
  bool send_to_charge(const planner::Config& positions);
  void refresh_goals(const planner::Config& positions);

  UrgencyOptions urgency_;
  long now_ = 0;  // step of the current start()/update(), for the history
  bool goals_changed_ = false;
  std::vector<char> at_goal_;  // queues / parking: stood on its goal at the last update
  std::vector<TaskRecord> revealed_;
  std::vector<Assignment> assignments_;
  std::vector<Task> slots_;
  std::vector<int> free_slots_;
  planner::Config goals_;
  long errands_finished_ = 0, tasks_finished_ = 0, tasks_assigned_ = 0;
};

}  // namespace tasks
