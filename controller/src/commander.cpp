#include "controller/commander.hpp"

#include <algorithm>
#include <cmath>

#include "controller/sumo_error.hpp"
#include "planner/heading.hpp"

namespace controller {

Commander::Commander(const gridify::CellMap& map, SumoBackend& sumo, double tick_s)
    : map_(map), sumo_(sumo), tick_(tick_s)
{
  for (const gridify::Aisle& a : map.aisles) {
    lanes_[a.lane_ab] = Lane{a.ab, a.length_ab, a.lane_ba, a.cells.back(), a.speed_ab};
    edge_lane_[a.ab] = a.lane_ab;
    // On a lattice net every aisle runs along one axis: its lanes face two opposite headings
    // (from two consecutive cells on the graph: an end junction gridify dropped is -1); a
    // one-way aisle has its A->B lane only.
    for (size_t k = 0; map.graph.is_grid() && k + 1 < a.cells.size(); ++k) {
      if (a.cells[k] < 0 || a.cells[k + 1] < 0) continue;
      const int h = planner::heading_of_move(map.graph, a.cells[k], a.cells[k + 1]);
      lane_heading_[a.lane_ab] = h;
      if (!a.one_way && !a.lane_ba.empty()) lane_heading_[a.lane_ba] = planner::reversed(h);
      break;
    }
    if (a.one_way) continue;  // no B->A lane (the planner never reverses on it)
    lanes_[a.lane_ba] = Lane{a.ba, a.length_ba, a.lane_ab, a.cells.front(), a.speed_ba};
    edge_lane_[a.ba] = a.lane_ba;
  }
  for (const gridify::Cell& c : map.cells)
    for (const gridify::Movement& m : c.movements) next_edges_[m.from].push_back(m.to);
  // Turns the planner may ask for but SUMO has no connection for: out of a junction cell
  // from any incoming lane into any linked aisle, and reversals inside aisles.
  for (planner::Vertex u = 0; u < map.graph.size(); ++u) {
    const gridify::Cell& c = map.cells[u];
    if (c.kind != gridify::CellKind::Junction) continue;
    for (const gridify::SumoPose& in : c.poses)
      for (planner::Vertex w : map.graph.neighbors(u)) {
        const std::string& out_lane = map.pose_entering(u, w).lane;
        const Lane &here = lane(in.lane), &out = lane(out_lane);
        if (connected(here.edge, out.edge)) continue;
        missing_turns_ = true;
        // Back into the aisle it came from is a turn in place; any other turn a jump.
        if (out_lane != here.opposite && jump_turn_.empty())
          jump_turn_ = "junction '" + c.junction + "': no SUMO connection from lane 0 of edge '" + here.edge +
                       "' to lane 0 of edge '" + out.edge +
                       "' (AGVs drive lane 0 only; an AGV would have to jump: rebuild the net with every turn "
                       "connected between lanes 0, gridify/README.md)";
      }
  }
  for (const gridify::Aisle& a : map.aisles)
    if (a.steps > 1 && !a.one_way && (!connected(a.ab, a.ba) || !connected(a.ba, a.ab))) missing_turns_ = true;
}

const Commander::Lane& Commander::lane(const std::string& id) const
{
  auto it = lanes_.find(id);
  if (it == lanes_.end()) throw ControlError("lane '" + id + "' is not on a kept aisle of the grid");
  return it->second;
}

bool Commander::connected(const std::string& from, const std::string& to) const
{
  auto it = next_edges_.find(from);
  if (it == next_edges_.end()) return false;
  for (const std::string& e : it->second)
    if (e == to) return true;
  return false;
}

std::string Commander::net_problem() const
{
  for (const gridify::Aisle& a : map_.aisles)
    for (const std::string& e : {a.ab, a.ba}) {
      if (e.empty()) continue;
      auto it = next_edges_.find(e);
      if (it == next_edges_.end() || it->second.empty())
        return "edge '" + e + "' has no SUMO connection onwards (a dead end without a turnaround: rebuild with " +
               "netconvert --no-turnarounds.geometry false, gridify/README.md)";
    }
  return jump_turn_;  // (the constructor's scan of the junction turns)
}

const std::string& Commander::continuation(const std::string& edge) const
{
  auto it = next_edges_.find(edge);
  if (it == next_edges_.end() || it->second.empty())
    throw ControlError("edge '" + edge + "' has no SUMO connection onwards: an AGV there would leave the network");
  for (const std::string& e : it->second)
    if (std::find(avoid_.begin(), avoid_.end(), e) == avoid_.end()) return e;
  return it->second.front();
}

void Commander::set_speed(Agv& a, double v)
{
  if (a.speed == v) return;  // scheme S: only state changes cost a call
  sumo_.set_speed(a.id, v);
  a.speed = v;
  ++stats_.speed;
}

void Commander::set_route(Agv& a, std::vector<std::string> edges)
{
  // SUMO 1.15's setRoute prepends every edge the vehicle has passed: over a lifelong run
  // each AGV's route (and each copy of it) grows without end (33 MB over 5000 ticks at
  // 1000 AGVs). A route named once per edge sequence and set by id is not extended, and
  // the few distinct sequences (net-sized) are shared by every AGV.
  std::string key;
  for (const std::string& e : edges) key += e + ' ';
  auto it = routes_.find(key);
  if (it == routes_.end()) {
    it = routes_.emplace(key, "rt" + std::to_string(routes_.size())).first;
    sumo_.add_route(it->second, edges);
  }
  sumo_.set_route_id(a.id, it->second);
  ++stats_.route;
}

void Commander::insert(const planner::Config& starts)
{
  agv_.clear();
  ids_.clear();
  for (int i = 0; i < static_cast<int>(starts.size()); ++i) {
    Agv a;
    a.id = vehicle_id(i);
    // Any pose of the start cell will do; the first heads A->B (aisles) or comes in over
    // the first kept incoming edge (junctions).
    a.pose = map_.cells[starts[i]].poses.front();
    const std::string& edge = lane(a.pose.lane).edge;
    const std::string route = "r_" + a.id;
    sumo_.add_route(route, {edge, continuation(edge)});
    sumo_.add_vehicle(a.id, route, "agv", 0, a.pose.pos);
    // Works on a vehicle that is still pending insertion.
    sumo_.set_speed_mode(a.id, 0);
    sumo_.set_speed(a.id, 0);
    ids_.push_back(a.id);
    agv_.push_back(a);
  }
}

void Commander::failed(int agent, const SumoError& e)
{
  const std::string& id = agv_[agent].id;
  if (!sumo_.running()) throw e;  // the connection is gone: that is the error
  const std::vector<std::string> ids = sumo_.vehicles();  // throws again if SUMO itself is gone
  if (std::find(ids.begin(), ids.end(), id) == ids.end())
    throw FleetError("AGV " + id + " (agent " + std::to_string(agent) +
                     ") is not in SUMO any more (removed behind the controller's back?)");
  throw e;
}

void Commander::command(const planner::Config& cur, const planner::Config& next, int ticks)
{
  for (int i = 0; i < static_cast<int>(agv_.size()); ++i) {
    try {
      command(i, cur[i], next[i], ticks);
    } catch (const SumoError& e) {
      failed(i, e);
    }
  }
}

void Commander::command(int i, planner::Vertex u, planner::Vertex v, int ticks)
{
  {
    // SUMO adds v * step_length per step: with a step length that is no binary fraction
    // (0.1) the steps can sum to an ulp past the target -- onto the next lane at a lane's
    // end, a re-sync. Aim a hair (1e-12 relative) short: far inside the tolerance.
    const double tick_ = this->tick_ * ticks * (1 + 1e-12);
    Agv& a = agv_[i];
    a.move_d = 0;
    if (u == v) {
      set_speed(a, 0);
      return;
    }
    // With headings, an AGV only drives the way it faces (SUMO shows that heading).
    if (!heading_.empty() && planner::heading_of_move(map_.graph, u, v) != heading_[i])
      throw ControlError("agent " + std::to_string(i) + " moves " + std::to_string(u) + " -> " + std::to_string(v) +
                         " facing " + planner::kHeadingLetter[heading_[i]] + ", not that way");
    const gridify::SumoPose target = map_.pose_entering(u, v);
    const Lane& here = lane(a.pose.lane);
    if (a.held || a.held_mm) {
      // Held at its heading's angle, SUMO moved a front at the lane's end 1 mm back: the
      // move starts from the exact cell centre, or it lands 1 mm short.
      unhold(a, true);
      a.held_mm = false;
    }
    if (target.lane == a.pose.lane) {
      // Along the lane; the route already continues past its end.
      set_speed(a, (target.pos - a.pose.pos) / tick_);
    } else if (map_.cells[u].kind == gridify::CellKind::Junction) {
      const std::string& out = lane(target.lane).edge;
      set_route(a, {here.edge, out, continuation(out)});
      if (connected(here.edge, out)) {
        set_speed(a, target.pos / tick_);
      } else if (target.lane == here.opposite) {
        // Back into the aisle it came from, without a turnaround connection: turn round on
        // the junction (as inside an aisle), then drive.
        set_speed(a, (target.pos - turn_round(a, here, target)) / tick_);
      } else {
        // No SUMO connection for this turn (net_problem() refuses such nets): jump there
        // now (SUMO runs with --ignore-route-errors in this case).
        jump(a, target);
        set_speed(a, 0);
      }
    } else if (target.lane == here.opposite) {
      // Reversal inside an aisle: turn the vehicle round on the spot, then drive.
      const double turned = turn_round(a, here, target);
      set_speed(a, (target.pos - turned) / tick_);
    } else {
      throw ControlError("agent " + std::to_string(i) + ": no scheme-S command for the move " + std::to_string(u) +
                         " -> " + std::to_string(v) + " from lane " + a.pose.lane);
    }
    a.move_d = a.speed * tick_;
    a.pose = target;
  }
}

double Commander::travel_left(const Agv& a, const VehiclePose& p) const
{
  if (p.lane == a.pose.lane) return std::max(0.0, a.pose.pos - p.pos);
  auto it = lanes_.find(p.lane);
  if (it == lanes_.end()) return a.move_d;  // not on a lane of the move: no progress counted
  return std::max(0.0, it->second.length - p.pos) + a.pose.pos;
}

double Commander::progress(const std::vector<VehiclePose>& now) const
{
  double least = 1;
  for (size_t i = 0; i < agv_.size(); ++i)
    if (agv_[i].move_d > 0) least = std::min(least, 1 - travel_left(agv_[i], now[i]) / agv_[i].move_d);
  return std::max(0.0, least);
}

void Commander::pace(const std::vector<VehiclePose>& now, double target, double dt)
{
  for (size_t i = 0; i < agv_.size(); ++i) {
    Agv& a = agv_[i];
    if (a.move_d <= 0) continue;
    const double left = travel_left(a, now[i]);
    const double v = std::max(0.0, std::min(left, left - (1 - target) * a.move_d)) / dt;
    try {
      // Sent even if it equals the last command: another client may have set another.
      sumo_.set_speed(a.id, v);
    } catch (const SumoError& e) {
      failed(static_cast<int>(i), e);
    }
    a.speed = v;
    ++stats_.speed;
  }
}

int Commander::lane_ticks(int i, planner::Vertex u, planner::Vertex v) const
{
  if (u == v) return 1;
  const Agv& a = agv_[i];
  const gridify::SumoPose target = map_.pose_entering(u, v);
  const Lane& here = lane(a.pose.lane);
  const Lane& to = lane(target.lane);
  // The front's travel, as command() commands it.
  double d = 0;
  if (target.lane == a.pose.lane)
    d = target.pos - a.pose.pos;
  else if (map_.cells[u].kind == gridify::CellKind::Junction && connected(here.edge, to.edge))
    d = target.pos;
  else if (target.lane == here.opposite)
    d = target.pos - (to.length - a.pose.pos);  // turned round where it stands, then driven
  if (!(d > 0) || !(to.speed > 0)) return 1;  // a jump (or nothing to drive)
  return std::max(1, static_cast<int>(std::ceil(d / (to.speed * tick_) - 1e-9)));
}

std::vector<int> Commander::start_headings(const planner::Config& starts) const
{
  std::vector<int> h;
  for (planner::Vertex v : starts) {
    auto it = lane_heading_.find(map_.cells[v].poses.front().lane);
    if (it == lane_heading_.end()) throw ControlError("headings need a lattice net: cell " + std::to_string(v) + " has none");
    h.push_back(it->second);
  }
  return h;
}

void Commander::use_headings(const std::vector<int>& start, int turn_steps)
{
  heading_ = start;
  turn_steps_ = std::max(1, turn_steps);
}

void Commander::turn(const std::string& actions, const std::vector<double>& factors)
{
  for (int i = 0; i < static_cast<int>(agv_.size()); ++i) {
    const char act = actions[static_cast<size_t>(i)];
    if (act == 'R' || act == 'C') begin_turn(i, act, factors.empty() ? 1.0 : factors[static_cast<size_t>(i)]);
  }
}

void Commander::begin_turn(int i, char act, double factor)
{
  Agv& a = agv_[i];
  a.turn_steps = factor >= 1 ? turn_steps_ : static_cast<int>(std::ceil(turn_steps_ / factor - 1e-9));
  a.turn_from = sumo_angle(heading_[i]);
  a.turn_by = act == 'R' ? 90.0 : -90.0;  // clockwise: SUMO's angle grows
  heading_[i] = planner::heading_after(heading_[i], act);
  ++stats_.quarter_turns;
  a.turn_step = 1;  // the first of turn_steps_ steps runs next
}

int Commander::move_heading(planner::Vertex u, planner::Vertex v) const { return planner::heading_of_move(map_.graph, u, v); }

double Commander::angle(int i)
{
  try {
    return sumo_.angle(agv_[i].id);
  } catch (const SumoError& e) {
    failed(i, e);
  }
}

void Commander::unhold(Agv& a, bool exact)
{
  const std::string& edge = lane(a.pose.lane).edge;
  set_route(a, {edge, continuation(edge)});
  if (exact) {
    sumo_.move_to(a.id, a.pose.lane, a.pose.pos);
    ++stats_.move_to;
  }
  a.held = false;
}

void Commander::orient(const std::vector<uint8_t>* hold)
{
  for (int i = 0; i < static_cast<int>(agv_.size()); ++i) {
    Agv& a = agv_[i];
    try {
      double angle = 0;
      if (a.turn_step > 0 && hold && (*hold)[i]) {
        angle = a.turn_from + a.turn_by * (a.turn_step - 1) / a.turn_steps;  // held where it got to
      } else if (a.turn_step > 0) {
        angle = a.turn_from + a.turn_by * a.turn_step / a.turn_steps;
        a.turn_step = a.turn_step >= a.turn_steps ? 0 : a.turn_step + 1;
      } else if (auto it = lane_heading_.find(a.pose.lane); it == lane_heading_.end() || heading_[i] != it->second) {
        angle = sumo_angle(heading_[i]);
      } else {
        // SUMO draws it along its lane again: that is its heading. The 1 mm back at a lane
        // end stays until it moves (command()); verify() accepts it meanwhile.
        if (a.held) unhold(a, false);
        continue;
      }
      // The route SUMO keeps through the coming moveToXY (keepRoute 0) is just this edge,
      // whatever the route before. Held since the last step (the last set_angle cut the
      // route to the edge): the route is that already, and moveTo back onto the same edge
      // and moveToXY onto the same point need no other, so no setRouteID (a replaceRoute
      // in SUMO: ~5 % of a 1000-AGV pibt-rot run's CPU, with every animated turn step).
      // Not held: a route that goes on past the lane (one a move left, or none set).
      if (!a.held) unhold(a, false);
      const Lane& here = lane(a.pose.lane);
      double dx = 0, dy = 0, back = a.pose.pos - 1e-4;
      if (a.pose.pos > here.length - 2e-3) {
        // At the lane's end SUMO puts the front 1 mm back (it clamps to length - 0.001):
        // aim past the end, from behind that point.
        back = here.length - 1.5e-3;
        const int h = lane_heading_.count(a.pose.lane) ? lane_heading_.at(a.pose.lane) : 0;
        dx = 0.01 * planner::kHeadingDx[h];
        dy = -0.01 * planner::kHeadingDy[h];  // the lattice's rows grow southward, SUMO's y northward
      }
      sumo_.set_angle(a.id, a.pose.lane, here.edge, a.pose.pos, back, std::fmod(angle + 360.0, 360.0), dx, dy);
    } catch (const SumoError& e) {
      failed(i, e);
    }
    a.held = a.held_mm = true;
    ++stats_.angle;
  }
}

void Commander::jump(Agv& a, const gridify::SumoPose& target)
{
  sumo_.move_to(a.id, target.lane, target.pos);
  ++stats_.move_to;
  ++stats_.jumps;
}

double Commander::turn_round(Agv& a, const Lane& here, const gridify::SumoPose& target)
{
  const Lane& back = lane(target.lane);
  const double turned = back.length - a.pose.pos;
  set_route(a, {here.edge, back.edge, continuation(back.edge)});
  sumo_.move_to(a.id, target.lane, turned);
  ++stats_.move_to;
  ++stats_.turns;
  stats_.flips += heading_.empty();  // with headings it has turned round on the cell already
  return turned;
}

bool Commander::needs_rest(int i, planner::Vertex u, planner::Vertex v) const
{
  const Agv& a = agv_[i];
  const gridify::SumoPose target = map_.pose_entering(u, v);
  if (target.lane == a.pose.lane) return false;
  const Lane& here = lane(a.pose.lane);
  if (map_.cells[u].kind == gridify::CellKind::Junction) return !connected(here.edge, lane(target.lane).edge);
  return true;  // reversal inside an aisle
}

void Commander::drive(int i, double speed, bool resend)
{
  try {
    if (resend) agv_[i].speed = -1;
    set_speed(agv_[i], speed);
  } catch (const SumoError& e) {
    failed(i, e);
  }
}

double Commander::move_length(int i, planner::Vertex u, planner::Vertex v) const
{
  const Agv& a = agv_[i];
  const gridify::SumoPose target = map_.pose_entering(u, v);
  if (target.lane == a.pose.lane) return std::max(0.0, target.pos - a.pose.pos);
  if (map_.cells[u].kind == gridify::CellKind::Junction && connected(lane(a.pose.lane).edge, lane(target.lane).edge))
    return target.pos;
  return 0;
}

double Commander::begin_move(int i, planner::Vertex u, planner::Vertex v)
{
  Agv& a = agv_[i];
  try {
    // With headings, an AGV only drives the way it faces (the Driver turns it first).
    if (!heading_.empty() && planner::heading_of_move(map_.graph, u, v) != heading_[i])
      throw ControlError("agent " + std::to_string(i) + " moves " + std::to_string(u) + " -> " + std::to_string(v) +
                         " facing " + planner::kHeadingLetter[heading_[i]] + ", not that way");
    if (!heading_.empty() && (a.held || a.held_mm)) {
      // Held at its heading's angle (it turned on its cell): the move starts from the exact
      // cell centre, as in command().
      unhold(a, true);
      a.held_mm = false;
    }
    const gridify::SumoPose target = map_.pose_entering(u, v);
    const Lane& here = lane(a.pose.lane);
    double d = 0;
    if (target.lane == a.pose.lane) {
      d = target.pos - a.pose.pos;
    } else if (map_.cells[u].kind == gridify::CellKind::Junction) {
      const std::string& out = lane(target.lane).edge;
      set_route(a, {here.edge, out, continuation(out)});
      if (connected(here.edge, out)) {
        d = target.pos;
      } else if (target.lane == here.opposite) {
        d = target.pos - turn_round(a, here, target);  // back into its aisle: turn in place
      } else {
        jump(a, target);  // a real jump: counted, reported (net_problem() refuses such nets)
      }
    } else if (target.lane == here.opposite) {
      // Turn in place: the AGV stands on its cell (needs_rest); its front stays on the
      // cell centre, only the lane (heading) changes. No distance is covered.
      d = target.pos - turn_round(a, here, target);
    } else {
      throw ControlError("agent " + std::to_string(i) + ": no command for the move " + std::to_string(u) + " -> " +
                         std::to_string(v) + " from lane " + a.pose.lane);
    }
    a.pose = target;
    return d;
  } catch (const SumoError& e) {
    failed(i, e);
  }
}

void Commander::verify(const planner::Config& at, double tol)
{
  (void)at;  // the commanded poses already encode `at`; kept for the call's meaning
  std::vector<VehiclePose> now;
  try {
    now = sumo_.poses(ids_);
  } catch (const SumoError& e) {
    // A getter failed: name the AGV that is gone, if one is (else it is SUMO's error).
    if (!sumo_.running()) throw;
    const std::vector<std::string> present = sumo_.vehicles();
    for (int i = 0; i < static_cast<int>(agv_.size()); ++i)
      if (std::find(present.begin(), present.end(), agv_[i].id) == present.end()) failed(i, e);
    throw;
  }
  verify(now, tol);
}

void Commander::verify(const std::vector<VehiclePose>& now, double tol)
{
  for (int i = 0; i < static_cast<int>(agv_.size()); ++i) {
    Agv& a = agv_[i];
    const VehiclePose& p = now[i];
    if (p.lane.empty())
      throw FleetError("AGV " + a.id + " (agent " + std::to_string(i) +
                       ") is not in SUMO any more (removed behind the controller's back?)");
    const double err = p.lane == a.pose.lane ? std::fabs(p.pos - a.pose.pos) : INFINITY;
    // Held at an angle (set_angle), SUMO keeps a front at the lane's end 1 mm back
    // (POSITION_EPS): that AGV stands on its cell; its next move starts exactly (command()).
    if (a.held_mm && err <= 1.1e-3) continue;
    if (err <= tol) {
      if (err > stats_.max_error) stats_.max_error = err;
      continue;
    }
    // Off its cell: put it back (the route of every AGV contains its commanded lane).
    try {
      sumo_.move_to(a.id, a.pose.lane, a.pose.pos);
    } catch (const SumoError& e) {
      failed(i, e);
    }
    ++stats_.move_to;
    ++stats_.resyncs;
  }
}

}  // namespace controller
