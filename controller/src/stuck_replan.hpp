#pragma once
// StuckWatch: rerouting around a stuck AGV in the adg executor (run.replan_on_stuck).
//
// Without it, an AGV stuck for a minute makes every AGV whose ADG actions depend on it
// wait, and the planner's commits stop run.window configurations ahead (every committed
// configuration contains the stuck AGV's planned moves): nobody routes around it. With it:
//
//   detect : after every SUMO step, an AGV whose next committed move is running or
//            released (it may go) but whose front has not moved for run.stuck_after_s
//            seconds is stuck (an AGV waiting on its dependencies is not) -- once another
//            AGV's next move waits for it (a hand-over it owes): else there is nothing to
//            route around, and a replan only costs (it restarts the search);
//   replan : at once, Run::replan(): the committed plan is cut at each AGV's progress
//            (still a valid plan, see replan()), the moves in progress stay in progress,
//            a fresh planner starts where they end with the stuck AGVs immobile
//            (planner/immobile.hpp: never moved, never pushed; the others head for their
//            goals around them), and a new ADG holds the moves in progress, then its commits;
//   recover: an immobile AGV that reports itself ready again (its delay has ended:
//            DelayModel::stopped() stands for the AGV's status message) -> the planner
//            marks it mobile and searches on from its current configuration (the end of
//            the committed window: it keeps the AGV in place, still a valid plan); only
//            when some AGV becomes stuck at the same step is it a full replan.
// Moves in progress: an AGV driving u -> v (maybe with a chained v -> w) is on its last
// target for the planner, and the new ADG begins with those moves as its first steps,
// running (rotation groups re-form: their moves are one step). Their targets were handed
// over already; every planned entry into u (v) waits (type 2) until the AGV has arrived on
// v (w), so the cells an AGV spans stay its own until it has driven through them -- a stuck
// AGV braked between two cells included. Nobody has to stop for a replan.
// Completeness: between two replans the planner is a fresh RT-LaCAM, complete for that
// instance; the last replan has no immobile AGV, so from there RT-LaCAM's completeness and
// the ADG's deadlock freedom bring every AGV to its goal. Replans happen only on stuck
// events and recoveries: finitely often for finitely many finite delays.
// Safety is checked after every SUMO step as always; no moveTo anywhere.
#include <algorithm>
#include <string>
#include <vector>

#include "controller/sumo_backend.hpp"
#include "executor/adg.hpp"
#include "executor/delay_model.hpp"

namespace controller {

class StuckWatch {
 public:
  // learn: the threshold grows to twice the longest stall that ended by itself (the AGV moved
  // on without a replan) while it held somebody up -- the fleet's passing stops are not
  // "stuck" (run.stuck_learn). Such a stall is shorter than the threshold was, so the
  // threshold at most doubles per stop.
  StuckWatch(int n, double stuck_after_s, double dt, bool learn = false);
  double threshold_s() const { return learn_ ? std::max(after_s_, 2 * longest_free_) : after_s_; }

  // After a SUMO step: stall timers, new stuck AGVs, recoveries. Returns true when the
  // immobile set should change: replan() now with target(). `gated`: per agent, >= 0 while a
  // zone's mutex holds its next move (Driver::gated): waiting for a rule, not stuck.
  bool observe(const executor::Adg& adg, const std::vector<VehiclePose>& poses, const executor::DelayModel& delays,
               const std::vector<int>& gated);
  const std::vector<uint8_t>& target() const { return target_; }  // the immobile set to replan with
  const std::vector<uint8_t>& immobile() const { return immobile_; }
  void replanned();  // replan() done: target() is the immobile set now
  // Agent i's running actions, in order (the Driver runs at most two: a move and a chained one).
  static std::vector<int> running(const executor::Adg& adg, int i);
  // The slowest progress of the AGVs not immobile (Adg::progress): the commit window is
  // counted from it (an immobile AGV's running move must not hold the window).
  long long min_progress(const executor::Adg& adg) const;

  long long stuck_events() const { return stuck_events_; }  // AGVs found stuck
  std::string describe() const;  // "agv3 immobile, agv5 mobile again" for the log

 private:
  int n_;
  double after_s_, dt_;
  bool learn_;
  double longest_free_ = 0;  // the longest stall, s, that ended with the AGV moving on by itself
  std::vector<double> stall_s_;
  std::vector<VehiclePose> last_;
  std::vector<uint8_t> immobile_, target_;
  long long stuck_events_ = 0;
};

}  // namespace controller
