#pragma once
// GraphExecution: executes what a real-time planner commits on the MAPF graph itself,
// tick by tick, under a DelayModel -- the SUMO-free twin of the controller's executor, so
// rtlacam-lifelong / benches and SUMO runs can be compared under the same delay switches.
//
//   lockstep : the committed configurations are executed one after the other by all agents
//              together; a step ends when its slowest mover has arrived (a stopped mover
//              holds everybody: "all wait for the slowest").
//   adg      : the planner commits up to `window` configurations ahead of the slowest
//              agent into an Adg; every tick each agent that is not stopped starts its next
//              action once released, and arrives after DelayModel::move_ticks ticks of
//              progress. Agents progress asynchronously.
//   adg-follow : adg with moving-block following (Adg::released_following): a follower
//              travels while its leader does and arrives (in the same tick at the
//              earliest) once the leader has arrived, so a train moves together.
// In both a stopped agent stays put. positions() after each tick is the executed
// configuration: an agent counts as on its source cell until it has arrived, so the
// sequence of positions is itself a MAPF plan (tests validate it).
//
// Headings (a planner that plans rotation actions itself: pibt-rot, epibt, wppl; the twin of
// the controller's rotation runs). The committed configurations go to the Adg as cell plans
// (a turn is a wait there, as in the controller), and every robot has an executed heading:
//   adg    : before its next move u -> v a robot turns toward v, a quarter turn per
//            DelayModel::move_ticks ticks (a slowed robot turns slower, as in SUMO), also
//            while it waits for a dependency; with no move left it turns to the planner's
//            latest heading. A stopped robot does not turn. Turns the plan undoes (R then
//            C) are not executed, as the controller's Driver skips them.
//   lockstep : a step with turns lasts as long as its slowest turner or mover; every
//            robot ends the step with the planner's heading of that step.
// actions() then holds the executed LoRR letter of each robot for the tick (F on the tick
// it arrives, R / C when a quarter turn ends, W otherwise).
#include <functional>
#include <memory>
#include <string>

#include "executor/adg.hpp"
#include "executor/delay_model.hpp"
#include "executor/execution.hpp"
#include "planner/budget.hpp"
#include "planner/realtime_planner.hpp"
#include "planner/rotation/rotation_planner.hpp"

namespace executor {

struct ExecOptions {
  std::string mode = "adg";  // adg | adg-follow | lockstep
  int window = 4;            // W >= 1: committed configurations ahead of the slowest agent
};

// "" if usable, else "<key>: what is wrong".
std::string check(const ExecOptions& o);

struct ExecStats {
  long long ticks = 0;
  long long commits = 0;          // configurations committed by the planner
  long long moves = 0;            // actions completed
  long long dependency_waits = 0; // agent-ticks: not stopped, has a committed move, not released
  long long delay_ticks = 0;      // agent-ticks stopped (DelayModel)
  long long lockstep_waits = 0;   // lockstep: agent-ticks a ready mover waited for others
  long long turn_ticks = 0;       // headings (rotation solvers): robot-ticks spent turning
};

class GraphExecution : public Execution {
 public:
  GraphExecution(planner::RealtimePlanner& p, const DelaySpec& d, const ExecOptions& o);

  // The Execution seam. can_accept: lockstep, when the last configuration is executed;
  // adg, while fewer than `window` are ahead of the slowest agent. push: a configuration
  // the planner committed (lockstep: the next one all execute together; adg: appended to
  // the Adg). step: delays are drawn, released actions start, moves progress.
  bool can_accept() const override;
  void push(const planner::Config& next) override;
  void step() override;
  // One tick with the planner: it searches once with `b`, commits to keep the window full
  // (top_up), then step().
  void tick(const planner::Budget& b);
  // The planner commits to keep the window full, never a wait (that has no action; nothing
  // found beyond the root yet: search on). `on_commit(from, to)`, if given, sees each step
  // before it is committed (a caller's validator). A rotation planner commits one step per
  // call (it plans one step per search), turns-only steps included.
  using CommitHook = std::function<void(const planner::Config& from, const planner::Config& to)>;
  void top_up(const CommitHook& on_commit = {});
  // Every committed configuration executed and the planner stands on its goals.
  bool finished() const;
  const planner::Config& positions() const override { return pos_; }
  const ExecStats& stats() const { return st_; }
  const Adg& adg() const { return *adg_; }
  const DelayModel& delays() const { return delays_; }
  // Headings (a rotation planner only; else empty): executed, and this tick's letters.
  const std::vector<int>& headings() const override { return heading_; }
  const std::string& actions() const override { return actions_; }
  // New goals (lifelong): only where the committed window is fully executed, so the
  // planner's current configuration is where the agents really are.
  bool idle() const override { return adg_->done() && pending_.empty() && heading_ == plan_heading_; }

 private:
  void tick_adg();
  void tick_lockstep();
  int wanted_heading(int i) const;  // adg: toward the next move, else the planner's latest
  bool turn(int i);                 // adg: a tick of turning toward wanted_heading(i); true if it turned

  planner::RealtimePlanner& p_;
  ExecOptions o_;
  DelayModel delays_;
  std::unique_ptr<Adg> adg_;
  std::vector<int> left_;        // adg: ticks of progress the running action still needs
  planner::Config pos_;
  planner::Config pending_;      // lockstep: the committed configuration being executed (empty: none)
  int lock_done_ = 0;            // lockstep: ticks of progress made on it
  ExecStats st_;
  // Headings (rot_ only).
  planner::RotationPlanner* rot_ = nullptr;
  const planner::Graph* g_ = nullptr;
  std::vector<int> heading_;          // executed
  std::vector<int> plan_heading_;     // the planner's after the last push
  std::vector<int> pending_heading_;  // lockstep: the planner's after pending_
  std::vector<int> turn_done_;        // adg: ticks of progress on the quarter turn under way
  std::string actions_;
};

}  // namespace executor
