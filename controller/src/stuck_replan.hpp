#pragma once
// StuckWatch: rerouting around a stuck AGV in the adg executor (run.replan_on_stuck).
//
// Without it, an AGV stuck for a minute makes every AGV whose ADG actions depend on it
// wait, and the planner's commits stop run.window configurations ahead (every committed
// configuration contains the stuck AGV's planned moves): nobody routes around it. With it:
//
//   detect : after every SUMO step, an AGV whose next committed move is running or
//            released (it may go) but whose front has not moved for run.stuck_after_s
//            seconds is stuck (an AGV waiting on its dependencies is not);
//   drain  : the planner commits nothing more and the Driver starts no new move (hold);
//            the moves in progress finish (braking on their target cells): then every
//            AGV stands on a cell, and the ADG's guarantees held throughout;
//   replan : Run::replan(): the executed configuration E, the committed plan cut at each
//            AGV's progress (still a valid plan, ending at E: see replan()), a fresh
//            planner from E with the stuck AGVs immobile (planner/immobile.hpp: never
//            moved, never pushed; the others head for their goals around them), a new ADG
//            from E;
//   recover: an immobile AGV that reports itself ready again (its delay has ended:
//            DelayModel::stopped() stands for the AGV's status message) -> drain, and
//            replan with it mobile.
// Completeness: between two replans the planner is a fresh RT-LaCAM from E, complete for
// that instance; the last replan has no immobile AGV, so from there RT-LaCAM's
// completeness and the ADG's deadlock freedom bring every AGV to its goal. Replans happen
// only on stuck events and recoveries: finitely often for finitely many finite delays.
// Safety is checked after every SUMO step as always; no moveTo anywhere.
//
// An AGV stuck while driving (it braked between cells u and v, maybe with a chained move
// v -> w running too) keeps those cells: the planner places it on the last target, the new
// ADG begins with its running moves still running (replan()). Not handled: one stuck in a
// rotation group (its members brake together) -- it is not rerouted around, the ADG keeps
// the others waiting as without the replan (counted in stuck_mid_move).
#include <string>
#include <vector>

#include "controller/sumo_backend.hpp"
#include "executor/adg.hpp"
#include "executor/delay_model.hpp"

namespace controller {

class StuckWatch {
 public:
  StuckWatch(int n, double stuck_after_s, double dt);

  // After a SUMO step: stall timers, new stuck AGVs, recoveries. Returns true when the
  // fleet is drained and replan() should run now with target().
  bool observe(const executor::Adg& adg, const std::vector<VehiclePose>& poses, const executor::DelayModel& delays);
  bool holding() const { return draining_; }           // no commits while draining
  const std::vector<uint8_t>& target() const { return target_; }  // the immobile set to replan with
  const std::vector<uint8_t>& immobile() const { return immobile_; }
  void replanned();  // replan() done: target() is the immobile set now
  // Agent i's running actions (the Driver runs at most two: a move and a chained one).
  static std::vector<int> running(const executor::Adg& adg, int i);
  // A stuck AGV replan() can place: none of its running moves in a rotation group.
  static bool placeable(const executor::Adg& adg, int i);
  // The slowest progress of the AGVs not immobile (Adg::progress): the commit window is
  // counted from it (an immobile AGV's one running move must not hold the window).
  long long min_progress(const executor::Adg& adg) const;

  long long stuck_events() const { return stuck_events_; }  // AGVs found stuck (at rest)
  long long stuck_mid_move() const { return mid_move_; }    // found stuck, not placeable (above)
  std::string describe() const;  // "agv3 immobile, agv5 mobile again" for the log

 private:
  bool drained(const executor::Adg& adg) const;

  int n_;
  double after_s_, dt_;
  std::vector<double> stall_s_;
  std::vector<VehiclePose> last_;
  std::vector<uint8_t> immobile_, target_, counted_mid_;
  bool draining_ = false;
  long long stuck_events_ = 0, mid_move_ = 0;
};

}  // namespace controller
