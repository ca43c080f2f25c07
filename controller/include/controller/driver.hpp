#pragma once
// Driver: the adg executor on SUMO (run.executor: adg). Each AGV runs the actions the
// action dependency graph (executor/adg.hpp) releases to it, asynchronously, with physical
// motion: its speed follows a trapezoid -- up at `accel`, down at `decel`, capped at
// max_speed x its speed factor -- that always keeps it able to stop on the target cell of
// the last move it may make. SUMO integrates the motion (speedMode 0: the speed set is the
// speed driven, so the front lands on the cell exactly); the controller plays the AGV's
// on-board motion controller.
//
//   start : an AGV with no running move starts its next action once released and not
//           stopped by a delay (a reversal in an aisle: only after one step at rest);
//   chain : while driving, it may also start the action after the running one if that
//           one's hand-over dependency is done, so it need not brake on the cell between
//           (at most two moves ahead: the braking distance at 1 m/s and 1 m/s^2 is 0.5 m);
//   rotate: the members of a rotation group start together, drive at the slowest one's
//           pace, cover equal fractions of their moves (arrive together) and brake together;
//   stop  : a stopped AGV (DelayModel) brakes at `decel` where it is -- between cells is
//           safe, the ADG keeps both cells for it until it arrives;
//   finish: when the front reaches an action's target the action is done (its pose is
//           checked against SUMO to 1e-6 m).
// allowed() gives the cells each AGV may occupy now, for Safety.
#include <string>
#include <vector>

#include "controller/commander.hpp"
#include "executor/adg.hpp"
#include "executor/delay_model.hpp"

namespace controller {

struct DriveParams {
  double dt = 0.125;  // SUMO step, s
  double accel = 0.5, decel = 1.0, max_speed = 1.0;
  // Moving-block following (run.executor adg-follow): body length and the gap kept to a
  // leader's back, m.
  bool follow = false;
  double length = 0.8, margin = 0.1;
};

struct DriveStats {
  long long dependency_waits = 0;  // agent-steps with a committed move not yet released
  long long delay_steps = 0;       // agent-steps stopped by a delay
  long long chained = 0;           // moves started while driving (no stop in between)
  long long followed = 0;          // moves started while the cell's previous occupant was still leaving it
  double max_error = 0;            // |SUMO front - target| at arrivals, m
};

class Driver {
 public:
  Driver(Commander& cmd, executor::Adg& adg, const executor::DelayModel& delays, const DriveParams& p);

  // Before a SUMO step: start released moves, set every AGV's speed for the step.
  void before_step();
  // After it: advance each AGV by the distance driven, finish the moves it completed.
  void after_step(const std::vector<VehiclePose>& poses);
  // Cells agent i may occupy now: where it stands for the ADG plus its running moves' targets.
  std::vector<std::vector<planner::Vertex>> allowed() const;
  // Per AGV, the rotation group (executor::Adg) it takes part in -- of its running move, or
  // of its last move while other members still drive -- -1 if none: Safety lets the members
  // of one group share cell claims while they rotate.
  std::vector<int> groups() const;
  bool idle() const;  // no AGV running a move
  // Agent i's executor state in one line (where it is for the ADG, its running moves with
  // group and hand-over): appended to a Safety error.
  std::string describe(int i) const;
  const DriveStats& stats() const { return st_; }

 private:
  struct Agv {
    std::vector<int> run;       // running actions, oldest first (at most 2)
    std::vector<double> dist;   // their distances
    std::vector<gridify::SumoPose> target;  // their target poses
    double done = 0;            // distance covered in run[0]
    double v = 0;               // speed for the current step
    int rest_steps = 0;         // steps at rest since the last arrival
    std::string lane;           // SUMO lane of the front after the last step
  };
  void begin(int action);
  // How far agent's front is past the start of its running `action` (negative: not there yet).
  double ahead(int agent, int action) const;
  // Follow mode: how far agent i's front may still go (its leaders' backs minus margin).
  double room(int i) const;

  Commander& cmd_;
  executor::Adg& adg_;
  const executor::DelayModel& delays_;
  DriveParams p_;
  std::vector<Agv> agv_;
  std::vector<double> rem_;  // per agent: distance it may still drive (set in before_step)
  DriveStats st_;
};

}  // namespace controller
