#pragma once
// Commander: commanding scheme "S" (see /work/shared/notes/sumo-1.15.md and
// controller/README.md). SUMO moves the AGVs itself; the commander only changes a
// vehicle's speed, route or lane position when its state changes:
//   wait                          -> setSpeed(0)                     (if it was moving)
//   along its lane                -> setSpeed(d / tick)              (if it was not)
//   out of a junction cell        -> setRoute({in, out, cont}); setSpeed(d / tick)
//   reversal inside an aisle      -> setRoute({AB, BA, cont}); moveTo(BA_0, L - pos); setSpeed
//   turn on the cell (rotation solvers: headings below) -> moveToXY with the angle, every
//                                    SUMO step while it turns or faces off its lane
// where the route always ends with one more edge `cont` so no AGV ever reaches the end of
// its route (SUMO would remove it). Reference point: the vehicle FRONT sits on the cell
// centre; a junction cell is the end of the incoming lane. With speedMode 0 and a step
// length dividing the tick, SUMO lands every AGV exactly on its cell (verify() checks).
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "controller/sumo_backend.hpp"
#include "controller/sumo_error.hpp"
#include "gridify/cell_map.hpp"
#include "planner/config.hpp"

namespace controller {

struct CommandStats {
  long long speed = 0, route = 0, move_to = 0;  // calls sent
  long long jumps = 0;     // turns SUMO has no connection for: done by moveTo at once
  long long resyncs = 0;   // verify() found an AGV off its cell and moved it back
  long long turns = 0;     // in-aisle reversals: moveTo onto the opposite lane at the mirrored
                           // position of an AGV standing on its cell (front stays put)
  double max_error = 0;    // largest position error seen by verify(), metres
  long long angle = 0;     // set_angle calls (moveToXY): AGVs turning or facing off their lane
  long long quarter_turns = 0;  // rotation solvers' turn actions executed (R, C), each turn_s long
  long long flips = 0;     // of `turns`, those of an AGV without a heading: an instant 180-degree flip in SUMO
  long long total() const { return speed + route + move_to + angle; }
};

class Commander {
 public:
  Commander(const gridify::CellMap& map, SumoBackend& sumo, double tick_s);

  static std::string vehicle_id(int agent) { return "agv" + std::to_string(agent); }

  // Adds one vehicle per agent (type "agv") with its front on the start cell, speedMode 0
  // and speed 0. They enter the network at the next SUMO step.
  void insert(const planner::Config& starts);

  // Commands for the move cur -> next (one tick; `ticks` > 1: stretched over that many
  // ticks, all AGVs at 1 / ticks of the speed). Agents with cur == next wait.
  void command(const planner::Config& cur, const planner::Config& next, int ticks = 1);

  // adg executor: prepares the move u -> v of one AGV whose commanded pose is cell u
  // (route, or the turn of a reversal) and returns the distance its front travels. The
  // speed is the caller's (drive()). A reversal or an unconnected turn needs the AGV at
  // rest on u (needs_rest()): the front does not move, only the heading flips.
  double begin_move(int agent, planner::Vertex u, planner::Vertex v);
  bool needs_rest(int agent, planner::Vertex u, planner::Vertex v) const;
  // What begin_move() would return for a driven move (on the lane, or through a connected
  // junction), without preparing it; 0 for one it would turn or jump (a lower bound).
  double move_length(int agent, planner::Vertex u, planner::Vertex v) const;
  // The move u -> v leaves the lane of the commanded pose (a new route): SUMO replaces a
  // route only from the edge the vehicle is on, so a chained move may only do that once the
  // AGV has reached the commanded lane.
  // The speed limit of a kept lane (the net's lane `speed`), m/s: the adg Driver never
  // commands more on it.
  double lane_speed(const std::string& lane_id) const { return lane(lane_id).speed; }
  // Lockstep: the ticks the move u -> v of an AGV commanded to cell u needs so that its
  // speed keeps to the limit of the lane it drives on (its target pose's lane: along a lane,
  // out of a junction and after a reversal the front travels on that lane only); 1 for a
  // wait or a jump. command() with at least this many ticks never exceeds the lane's speed.
  int lane_ticks(int agent, planner::Vertex u, planner::Vertex v) const;
  bool changes_lane(int agent, planner::Vertex u, planner::Vertex v) const
  {
    return map_.pose_entering(u, v).lane != agv_[agent].pose.lane;
  }
  // Sets the speed for the next step. SUMO keeps a speed until it is set again, and another
  // TraCI client may have changed it: `resend` sets it even if it equals the last command.
  void drive(int agent, double speed, bool resend = false);
  // Headings (rotation solvers; planner/heading.hpp: 0 east .. 3 north). An AGV faces
  // along its lane unless it turned on its cell: a turn action (R, C) keeps it on the cell
  // while its SUMO angle turns 90 degrees over `turn_steps` SUMO steps (orient() before each
  // step); an AGV facing off its lane is held at its heading's angle every step (SUMO
  // would draw the lane's). A later forward move (F) leaves along the heading, so the lane
  // it enters faces that way again. Needs a lattice net (map.graph.is_grid()).
  //
  // The heading of the lane of each cell's first pose (where insert() puts an AGV).
  std::vector<int> start_headings(const planner::Config& starts) const;
  void use_headings(const std::vector<int>& start, int turn_steps);
  bool headings() const { return !heading_.empty(); }
  // At a tick's start, with the executed rotation actions (F, R, C, W per agent) and the
  // agents' speed factors (begin_turn; empty: all 1).
  void turn(const std::string& actions, const std::vector<double>& factors = {});
  // One AGV's quarter turn (act R or C), as turn() does for each: the adg Driver turns an
  // AGV at rest toward its next move's direction. A slowed AGV (speed factor f in (0, 1],
  // executor/delay_model.hpp) turns slower too: ceil(turn_steps / f) SUMO steps.
  void begin_turn(int agent, char act, double factor = 1);
  // Its turn still animates (orient() has steps of it to run).
  bool turning(int agent) const { return agv_[agent].turn_step > 0; }
  // Before every SUMO step. `hold` (adg: AGVs stopped by a delay), per agent: a running
  // turn stays at the angle it has reached this step instead of going on.
  void orient(const std::vector<uint8_t>* hold = nullptr);
  int heading(int agent) const { return heading_[agent]; }
  // The lattice heading of the move u -> v (planner::heading_of_move on the map's graph).
  int move_heading(planner::Vertex u, planner::Vertex v) const;
  // SUMO's angle of the AGV now (the closed loop of a turn: the Driver reads where it got to).
  double angle(int agent);
  // SUMO's angle (0 north, 90 east) of a heading.
  static double sumo_angle(int heading) { return heading == 3 ? 0.0 : 90.0 + 90.0 * heading; }

  // SUMO ids in agent order.
  const std::vector<std::string>& ids() const { return ids_; }

  // After the tick: every AGV must be on the pose of its cell in `at` within `tol`
  // metres; off by more -> moveTo back (counted in resyncs). An AGV missing from SUMO is
  // a ControlError. Reads all poses with one SumoBackend::poses() call (request_poses()
  // before the tick's last step lets a back end batch it).
  void verify(const planner::Config& at, double tol);
  // The same with poses already read after the tick's last step (no second read).
  void verify(const std::vector<VehiclePose>& now, double tol);

  // Lock-step pacing: the closed loop of `command()` against stops the controller is not
  // told about (a person, a pallet, another TraCI client braking an AGV). progress(): the
  // least fraction of its commanded move that a mover has driven, from SUMO's poses (1 when
  // none moves). pace(): every mover's speed for the next SUMO step of `dt` s, so that it
  // reaches fraction `target` of its move (one ahead of it stands): the fleet keeps to its
  // slowest mover, as lock-step means, so a follower never runs into a leader held in the
  // cell it is leaving, and a held AGV drives on from where it stands once released.
  double progress(const std::vector<VehiclePose>& now) const;
  void pace(const std::vector<VehiclePose>& now, double target, double dt);

  // The commanded pose of an agent (where its front must be after the tick).
  const gridify::SumoPose& pose(int agent) const { return agv_[agent].pose; }
  const CommandStats& stats() const { return stats_; }
  // True if some turn the planner may use has no SUMO connection (SUMO then needs
  // --ignore-route-errors for the route that jumps it).
  bool needs_ignore_route_errors() const { return missing_turns_; }
  // "" or why the net cannot be driven: an aisle edge with no SUMO connection onwards (a
  // dead end without a turnaround): every route ends with one more edge, or SUMO removes
  // the AGV at the route's end. Checked before SUMO starts: a bad net is bad input.
  std::string net_problem() const;

 private:
  struct Agv {
    std::string id;
    gridify::SumoPose pose;  // commanded front position
    double speed = 0;        // last commanded speed
    double move_d = 0;       // command(): the front's travel of the move (0: it stands)
    bool held = false;       // set_angle before the last step: SUMO moved a lane-end front back
                             // 1 mm and cut the route to the current edge
    bool held_mm = false;    // held since its last move: its front may stand 1 mm back
    int turn_step = 0;       // steps of the running turn done (0: none running)
    int turn_steps = 1;      // steps of the running turn in all
    double turn_from = 0, turn_by = 0;  // SUMO angle at the turn's start, +-90
  };
  struct Lane {
    std::string edge;
    double length = 0;
    std::string opposite;    // lane of the opposite edge of the aisle
    planner::Vertex end = -1;  // junction cell at the end of the lane
    double speed = 0;          // the lane's speed limit, m/s
  };

  void command(int agent, planner::Vertex u, planner::Vertex v, int ticks);
  // Metres its front still has to go to its commanded pose (on that lane, or on the lane
  // before it).
  double travel_left(const Agv& a, const VehiclePose& p) const;
  // A SUMO call on an AGV failed: a ControlError if the AGV is gone, else rethrows.
  [[noreturn]] void failed(int agent, const SumoError& e);
  const Lane& lane(const std::string& id) const;
  const std::string& continuation(const std::string& edge) const;  // an edge SUMO may take after `edge`
 public:
  // Edges whose lane SUMO now disallows for the AGVs (rules.hpp, lanes closed over TraCI):
  // SUMO refuses any route through one, so a route's continuation avoids them.
  void avoid_edges(std::vector<std::string> edges) { avoid_ = std::move(edges); }

 private:
  std::vector<std::string> avoid_;
  bool connected(const std::string& from, const std::string& to) const;
  void set_speed(Agv& a, double v);
  void set_route(Agv& a, std::vector<std::string> edges);
  // After set_angle: the exact cell pose again and a route that goes on past its lane.
  void unhold(Agv& a, bool exact);
  // A moveTo that SUMO cannot drive (no connection for the turn): counted as a jump.
  void jump(Agv& a, const gridify::SumoPose& target);
  // Reversal inside an aisle: route onto the opposite lane and turn the AGV round where it
  // stands (front on the same point); returns its position on the opposite lane.
  double turn_round(Agv& a, const Lane& here, const gridify::SumoPose& target);

  const gridify::CellMap& map_;
  SumoBackend& sumo_;
  double tick_;
  std::unordered_map<std::string, Lane> lanes_;
  std::unordered_map<std::string, std::string> edge_lane_;
  std::unordered_map<std::string, std::vector<std::string>> next_edges_;  // SUMO connections
  std::unordered_map<std::string, int> lane_heading_;  // lattice heading of each aisle lane (grid nets)
  std::vector<int> heading_;  // per agent, with headings (empty without)
  int turn_steps_ = 1;
  bool missing_turns_ = false;
  std::string jump_turn_;  // the first junction turn only a jump could drive ("": none)
  std::unordered_map<std::string, std::string> routes_;  // edge sequence -> SUMO route id (set_route)
  std::vector<Agv> agv_;
  std::vector<std::string> ids_;  // SUMO ids of the agents, in agent order
  CommandStats stats_;
};

}  // namespace controller
