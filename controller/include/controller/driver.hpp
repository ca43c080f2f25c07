#pragma once
// Driver: the adg executor on SUMO (run.executor: adg | adg-follow). Each AGV runs the
// actions the action dependency graph (executor/adg.hpp) releases to it, asynchronously,
// with physical motion: its speed follows a trapezoid -- up at `accel`, down at `decel`,
// capped at max_speed x its speed factor -- that always keeps it able to stop at its
// stopping point. SUMO integrates the motion (speedMode 0: the speed set is the speed
// driven, so the front lands on the cell exactly); the controller plays the AGV's on-board
// motion controller.
//
//   start : an AGV with no running move starts its next action once released and not
//           stopped by a delay (a reversal in an aisle: only after one step at rest);
//   chain : continuous motion -- every later action of the AGV whose hand-over is met is
//           started too (a prefix of its remaining actions), so it drives through all
//           their cells and brakes only for the end of the last one. Not across a turn
//           that needs rest, and a move onto a new lane (new SUMO route) only once the AGV
//           is on the commanded lane (SUMO replaces a route from the current edge only).
//           In follow mode a move chains only if braking still stops behind its leader,
//           measured from the move's end (run.chain_to_end; Commander::move_length);
//   follow: adg-follow (moving-block following): a move into cell v may start (or chain)
//           once v's previous occupant has STARTED leaving it (toward another cell: the
//           plan has no swaps); the stopping point is then
//               min(end of the running moves, v + leader's distance past v - length - margin,
//                   [off run.gap_handover:] v - 1e-6 until the leader has arrived),
//           with the leader's body measured as if its path went straight on through v
//           (exact for a train; at a junction it only adds distance). So the front stays
//           `margin` (vType min_gap) behind the leader's back, and v is completed only after
//           the leader's arrival elsewhere, as in Hönig's ADG order (after_step);
//           gap hand-over (run.gap_handover): the body gap alone bounds the follower, not
//           "short of v until the leader has arrived" -- a front at v already puts the
//           leader's front length + margin past v, off v's line -- so a follower may reach v,
//           and chain on through it, while its leader covers its last centimetres. Without
//           it a link of a train often arrives a SUMO step after its leader, and those steps
//           add up along the plan's chains of hand-overs (large warehouse, same-step
//           hand-overs: 40 % a step behind without, 9 % with);
//           relative braking (run.relative_braking): once the follower is `margin` behind
//           the leader's back, the leader's distance counts its sure travel too (braking
//           at `decel` in whole steps from the speed SUMO reports: no command and no outside
//           stop brakes harder), and a leader sure to reach its target counts as arrived
//           for "short of v"; both brake at the same rate, so the gap is least now or at the
//           end -- trains run at speed one cell apart. A follower that reaches v first
//           completes its move only after the leader's (after_step: arrivals in ADG order);
//   passes: (run.same_step_starts) starts and chains are repeated within the step until none
//           is added, so a queue starts in one step, not one step per AGV;
//   rotate: the members of a rotation group start together (strictly released, also in
//           follow mode), drive at the slowest one's pace, cover equal fractions of their
//           moves (arrive together) and brake together;
//   stop  : a stopped AGV (DelayModel) brakes at `decel` where it is -- between cells is
//           safe, the ADG keeps both cells for it until it arrives;
//   finish: when the front reaches an action's target the action is done (its pose is
//           checked against SUMO to 1e-6 m);
//   turn  : AGVs with headings (rotation solvers, or a cell solver given fleet.turn_s;
//           Commander::use_headings): a move only
//           starts facing its direction. An AGV at rest whose next action points
//           elsewhere turns on its cell first, a quarter turn at a time (turn_toward), each
//           animated over fleet.turn_s (Commander::orient), before its action is released
//           too (it stands on its own cell, which the ADG keeps for it); a turn is done when
//           SUMO reports the AGV at the new heading's angle, a delay stops it where it got
//           to, and moves are never chained across a turn. The rotation plan's own turn
//           steps are waits in cell space: the ADG drops them and the Driver turns exactly
//           when a move needs it.
// Closed loop: after every step each AGV's progress along its running moves and its speed
// are read from SUMO (lane, position, speed), never taken from the speed commanded: an AGV
// held by anyone else (another TraCI client, a person in the aisle) makes no progress, its
// moves stay running and the ADG waits for it. Every command is feasible for the vType:
// within [v - decel dt, v + accel dt] of the speed SUMO reports and <= max_speed, and the
// stopping point is kept reachable by braking at `decel` in whole SUMO steps
// (stop_speed()), so no AGV brakes harder than its vType allows.
//
// Why adg-follow is collision-free: (1) ADG order -- an action into v completes only after
// v's previous occupant has arrived elsewhere, and (executor/adg.hpp) the previous occupants
// before it left before it entered, so at most two AGVs are ever near v: the one leaving
// and the one entering (plus rotation members, which move as one); (2) gap invariant -- the
// follower's stopping point is behind the leader's back minus margin, and it never
// decreases (a leader only moves forward, stopped or not), so braking at `decel` from a
// speed <= sqrt(2 decel room) always stops in time; a stopped leader only freezes the
// follower's stopping point. Safety (safety.hpp) checks the bodies independently.
// Why it progresses under finite delays: following only relaxes when a move may START; its
// completion still waits for the same ADG dependencies, so the dependency graph is the same
// DAG (rotation cycles grouped) and the strict ADG's deadlock freedom carries over: the
// earliest undone action's leader is done, so its stopping point is its cell and it
// arrives once its delays end; with RT-LaCAM's completeness every committed step is
// eventually executed and the goals are reached (tests/controller/test_agv.cpp).
// allowed() gives the cells each AGV may occupy now, for Safety.
#include <array>
#include <functional>
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
  // Relative braking (follow mode): a follower counts on the distance its leader will
  // still cover braking at `decel` from the speed SUMO reports (no command brakes harder,
  // nor does an outside stop), and may enter the leader's cell once the leader is sure to
  // arrive. Off: brick-wall following (the leader could stop dead; the cell waits for its arrival).
  bool sure_travel = true;
  // The decel the sure travel is counted at (>= decel): a leader stopped harder than its own
  // decel from outside (8 m/s^2 against decel 1) left its follower too close (session 47).
  double leader_decel = 1.0;
  // Chaining into a leader's cell measures the stopping point from the end of the new move
  // (off: from its start, a move short -- a follower then stops at each cell behind a moving leader).
  bool exact_chain = true;
  // The hand-over is the body gap alone: a follower may reach v (and drive on) as soon as
  // its leader's back, plus the leader's sure travel, is `margin` past v -- also before the
  // leader has arrived at its next cell; only its completion waits for the leader's (after_step,
  // ADG order). Off: the follower stays short of v until the leader has arrived or is sure
  // to (each link of a train then arrives a SUMO step after its leader, and the lags add up
  // along the plan's hand-over chains).
  bool gap_handover = true;
  // Starts in passes within one SUMO step (a move released by another start this step starts too).
  bool same_step_starts = true;
  // Switchable ADG (run.switch_passages): a move that waits for another AGV's passage
  // through its cell, which that AGV has not begun, takes the cell first (Adg::try_switch).
  int switch_passages = 0;  // 0: off; else the late AGV's least number of moves before the cell
  // Lane speed limits (the net's lane `speed`): an AGV never drives faster than the limit
  // of the lane its front is on, and brakes in time (at `decel`, whole steps) for a slower
  // lane ahead on its running moves (reach_speed()).
  bool lane_speeds = true;
};

struct DriveStats {
  long long dependency_waits = 0;  // agent-steps with a committed move not yet released
  long long delay_steps = 0;       // agent-steps stopped by a delay
  long long chained = 0;           // moves started while driving (no stop in between)
  long long switches = 0;          // passages reordered (switch_passages)
  long long followed = 0;          // moves started while the cell's previous occupant was still leaving it
  double max_error = 0;            // |SUMO front - target| at arrivals, m
  double overshoot = 0;            // most a command ever drove past a stopping point, m (0: never)
  // Where the time goes: agent-steps of AGVs with a move running, by what bounds the speed
  // commanded (the first that applies): cruising at full speed, accelerating (accel
  // limit), braking / held short for a leader (follow room), for a lane's limit, for the end
  // of its released moves; and agent-steps at rest with a released move not started
  // (rotation members, rest before a reversal).
  struct Time {
    long long cruise = 0, accel = 0, follow = 0, lane = 0, end = 0, start_wait = 0;
  } time;
  long long turn_steps = 0;        // agent-steps turning on a cell toward the next move (headings)
  // Where each AGV's SUMO steps go, up to its last arrival (issue 21: ticks per plan step):
  // one category per agent-step, counted once the agent next arrives somewhere (steps after
  // its last arrival -- idle on its goal -- are never counted). Names: split_name().
  enum Split : int {
    kCruise,         // moving at top speed
    kAccel,          // moving, speed bounded by accel
    kFollow,         // moving, braking / held for a leader's back (follow room)
    kEndDep,         // moving, braking for the end of its released moves: the next move waits for a dependency
    kEndRest,        // ... the next move needs rest (a reversal, a turn) or the commanded lane
    kEndLast,        // ... no next move appended (plan wait not yet followed by a move, or its goal)
    kLane,           // moving, bounded by a lane's speed limit
    kGapStand,       // standing with a released move: the leader's back (body gap) holds it
    kFinishWait,     // front on its target, the move's completion waits for the leader's arrival (ADG order)
    kLeaderArriving, // standing, next move not released: the cell's previous occupant is still moving into it
    kLeaderWaiting,  // ... the previous occupant stands on the cell, its move out not released (its own dependency)
    kLeaderRule,     // ... the previous occupant's move out is released but not started (rest before a reversal, turn, group, zone)
    kLeaderDelayed,  // ... the previous occupant is stopped by a delay
    kLeaderStrict,   // ... a rotation group: strict release, the previous occupant's move out still running
    kOwnGroup,       // ... its own previous move's rotation group not done
    kStartRule,      // standing, next move released, not started (rest before a reversal, group, zone)
    kTurn,           // turning on its cell (headings)
    kDelay,          // stopped by a delay
    kNoActionGoal,   // standing on its goal, no next move appended yet (it will make way later)
    kNoAction,       // standing off its goal, no next move appended yet: execution is ahead of the commits (run.window)
    kSplitCount
  };
  static const char* split_name(int k);
  long long split[kSplitCount] = {};
  long long starts_from_rest = 0;  // moves started with the AGV at rest (not chained)
  // Starts from rest right after a no_action stretch (the move was released as soon as it was
  // committed: the window held the AGV), and the no_action steps before them.
  long long starved_starts = 0, starved_steps = 0;
};

// The highest speed for the next step from which braking at `decel` in whole steps of `dt`
// (v, v - decel dt, ..., 0; each step covers speed x dt) stops within `room` metres, and
// lands exactly on it when taken every step.
double stop_speed(double room, double decel, double dt);
// The highest speed from which braking at `decel` in whole steps of `dt` drives every step
// faster than `limit` within `room` (so the front crosses a boundary `room` ahead at
// <= limit); `limit` itself when room <= 0.
double reach_speed(double room, double limit, double decel, double dt);

class Driver {
 public:
  Driver(Commander& cmd, executor::Adg& adg, const executor::DelayModel& delays, const DriveParams& p);

  // Before a SUMO step: start released moves, set every AGV's speed for the step.
  void before_step();
  // After it: each AGV's progress and speed as SUMO reports them; finish the moves it completed.
  void after_step(const std::vector<VehiclePose>& poses);
  // Cells agent i may occupy now: where it stands for the ADG plus its running moves' targets.
  // Valid until the next call (one buffer, refilled: a SUMO step's 1000 small vectors are
  // not allocated again each step).
  const std::vector<std::vector<planner::Vertex>>& allowed() const;
  // Per AGV, the rotation group (executor::Adg) it takes part in -- of its running move, or
  // of its last move while other members still drive -- -1 if none: Safety lets the members
  // of one group share cell claims while they rotate.
  std::vector<int> groups() const;
  bool idle() const;  // no AGV running a move
  // Per agent, 1 while a delay stops it (Commander::orient holds its turn there).
  std::vector<uint8_t> stopped() const;
  // The ADG was rebuilt (a replan) with agent i's running moves as actions `ids`, in order:
  // a prefix of them (a stuck AGV drops the chained moves it has not begun).
  void renumber(int i, const std::vector<int>& ids)
  {
    Agv& g = agv_[i];
    g.run = ids;
    g.dist.resize(ids.size());
    g.target.resize(ids.size());
    g.from.resize(ids.size());
  }
  // Agent i's executor state in one line (where it is for the ADG, its running moves with
  // group and hand-over): appended to a Safety error.
  std::string describe(int i) const;
  const DriveStats& stats() const { return st_; }
  // One-at-a-time zones (controller/rules.hpp), the ADG side: `zone_of` (cell -> zone
  // indices; outlives the Driver, nullptr: none) makes every start and chain of a move into
  // a zone the AGV is not in wait while another AGV stands in that zone for the ADG (its
  // move out not yet done) or runs a move into it -- a mutex per zone, taken when the move
  // in starts and given back when the move out is done (so at most one front is ever near a
  // zone's cells). A move waiting for it is not stuck (stuck_replan.hpp); the planner hears
  // of long waits through gated() (Rules::count_held) and then routes around the zone.
  void set_zones(const std::vector<std::vector<int>>* zone_of) { zone_of_ = zone_of; }
  // Per agent, the zone whose mutex held its next move in the last before_step(), -1 if none.
  const std::vector<int>& gated() const { return gated_; }
  bool zone_gated() const { return zone_of_ != nullptr; }
  // Statistics only (DriveStats::split): agent i's goal now (unset: no goals known).
  void set_goal_of(std::function<planner::Vertex(int)> goal_of) { goal_of_ = std::move(goal_of); }
  // Statistics only: keep every agent-step's DriveStats::Split category, one letter per SUMO
  // step ('a' + category) per agent (scripts/closed_loop_decompose.py sums them along the
  // executed critical path).
  void set_trace(bool on) { trace_.assign(on ? agv_.size() : 0, std::string()); }
  const std::vector<std::string>& trace() const { return trace_; }

 private:
  struct Agv {
    std::vector<int> run;       // running actions, oldest first (chained: as many as are released)
    std::vector<double> dist;   // their distances
    std::vector<gridify::SumoPose> target;  // their target poses
    std::vector<gridify::SumoPose> from;    // the poses they start from
    double done = 0;            // distance covered in run[0] (from SUMO's pose)
    double v = 0;               // speed SUMO reported after the last step
    double cmd = 0;             // speed commanded for the last step
    int rest_steps = 0;         // steps at rest since the last arrival
    bool turning = false;       // a quarter turn commanded and not yet seen done in SUMO
    std::string lane;           // SUMO lane of the front after the last step
  };
  void begin(int action);
  // Starts agent i's next move if released and chains the released ones after it; true if
  // any started. count: add to the per-step stats (first pass only).
  bool start_moves(int i, bool count);
  // Finishes agent i's running moves its front has reached, in ADG order (may_finish); true if any.
  bool arrive(int i, const VehiclePose& pose);
  // Action id's rotation group (if any) has every other member done or with its front on its target.
  bool group_arrived(int id) const;
  // The zone mutex (set_zones): may agent i move from -> to now? Records gated_[i] if not.
  bool zone_free(int i, planner::Vertex from, planner::Vertex to);
  // Follow mode: the distance agent i's front still covers braking at `decel` in whole steps
  // from its reported speed (its next command is >= v - decel dt), and the length of its
  // running `action` (INFINITY if not running).
  double sure_travel(int i) const;
  double handover_dist(int agent, int action) const;
  // Headings: agent i (no running move) faces its next action's direction; if not, it
  // turns toward it when at rest (and returns false).
  bool faces(int i, int action);
  // How far agent's front is past the start of its running `action` (negative: not there yet).
  double ahead(int agent, int action) const;
  // Follow mode: how far agent i's front may still go (its leaders' backs minus margin).
  double room(int i) const;
  // Lane speed limits: the most agent i may drive now (DriveParams::lane_speeds).
  double lane_cap(int i) const;
  // How far past the start of action a's target cell the front may go: its leader's back
  // minus margin, short of the cell while the leader has not arrived; INFINITY without one.
  // end: the front's distance to a's target (relative braking only from a safe gap now).
  double gap(const executor::Action& a, double end) const;
  // Where SUMO's pose puts agent i's front along its running moves (distance from the
  // start of run[0]); NaN if it is on none of their lanes.
  double progress(int i, const VehiclePose& p) const;

  Commander& cmd_;
  executor::Adg& adg_;
  const executor::DelayModel& delays_;
  DriveParams p_;
  std::vector<Agv> agv_;
  std::vector<double> rem_;  // per agent: distance it may still drive (set in before_step)
  std::vector<char> waiting_start_;  // per agent: released, not started (DriveStats::Time)
  // DriveStats::split: this agent-step's category; counts held per agent until it next arrives.
  int split_of(int i, double v, int why) const;
  std::vector<std::array<long long, DriveStats::kSplitCount>> split_pending_;
  std::function<planner::Vertex(int)> goal_of_;
  std::vector<long long> noact_run_;  // per agent: consecutive no_action steps up to now
  std::vector<std::string> trace_;    // set_trace: per agent, one letter per SUMO step
  DriveStats st_;
  const std::vector<std::vector<int>>* zone_of_ = nullptr;
  std::vector<int> gated_;
  mutable std::vector<std::vector<planner::Vertex>> allowed_;  // allowed()'s buffer
};

}  // namespace controller
