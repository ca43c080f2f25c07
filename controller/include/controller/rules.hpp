#pragma once
// Rules: warehouse traffic rules at run time (issue 24), in cells of the gridified net.
//
// Closures. A closure closes cells for a time window [begin, end) (s). Sources:
//   - SUMO: a <rerouter> interval with <closingReroute>/<closingLaneReroute> in
//     sumo.additional (read before SUMO starts; gridify/rules_file.hpp);
//   - SUMO at run time: a lane whose permissions another TraCI client (or the test) changed
//     so that the AGVs' class ("passenger", the controller's vType) may not use it -- polled
//     once per tick on the lanes gridify mapped (rules.watch_lanes). SUMO itself then
//     refuses routes over it, so AGVs on such a lane wait there (frozen_cells());
//   - YAML: rules.closures [{lanes, edges, cells, begin, end}].
//   Closing every lane of an aisle (both of a two-way one) closes its interior cells; a
//   junction cell is closed when every aisle lane at it is closed. Closing one lane of a
//   two-way aisle (one edge: a closingReroute of one edge, a permission changed on one lane,
//   `lanes:` naming one direction) closes only that direction: the arcs along it, from its
//   first junction cell to its last (closed_arcs()); the cells stay usable the other way.
//   SUMO 1.15's rerouter does not show its closures in Lane.getAllowed (measured), hence the
//   file is read instead.
// One-at-a-time zones: a set of cells (an <poly type="rtlacam.zone"> in sumo.additional:
//   the cells whose centre lies inside; or rules.zones [{id, lanes, edges, cells}]) holding
//   at most one AGV at any time.
//
// How the controller keeps them:
//   - the planner plans on graph(): no arc into a closed cell (planner/blocked.hpp: AGVs on
//     a cell being closed leave it or wait), no arc closed one way, and no arc from outside
//     into a zone whose occupant keeps others waiting (blocked_zones()); a change of either
//     restarts the planner (a new epoch), so the search never carries a tree built on
//     another graph. Lockstep restarts it at the current configuration; adg / adg-follow
//     (Run::rules_tick_adg) replan from the observed state with the stuck-AGV replan
//     (stuck_replan.hpp, Run::replan with regraph): the committed plan is cut at each
//     AGV's progress, the moves in progress finish (a moving AGV cannot stop on a cell
//     boundary: one driving into a cell as it closes gets there, then leaves like one that
//     stood on it; RuleCheck excuses that entry), and the planner on the new graph starts
//     where they end, the stuck AGVs still immobile;
//   - rotation solvers (pibt-rot, epibt, wppl) restart the same way, each AGV also at its
//     heading: lockstep, the heading its executed actions left it with (a forward move held
//     by admit() keeps it); adg / adg-follow, the heading of its last move in progress, or
//     the one the Driver turned it to (Commander::heading) if none -- so no AGV's heading
//     flips or jumps at a restart, and the Driver turns it only where its next move needs;
//   - an AGV whose goal it cannot reach on that graph (its goal closed or cut off, or in an
//     occupied zone) waits: its planner goal becomes the nearest reachable cell that is
//     open, outside every zone and nobody's goal (goals()); one line names it when a
//     closure is the cause; a one-shot run is solved only once every AGV is on its real goal;
//   - the cell solvers plan the zones themselves (rules.plan_zones, on under lockstep by
//     default: planner/zones.hpp): no step they plan puts two AGVs in a zone, so admit()
//     below holds nobody and the search is never restarted for a zone;
//   - lockstep, admit(): the step the planner committed may still take two AGVs into a free
//     zone at once (rules.plan_zones off, rotation solvers); all but one are held (with
//     whoever would move into a held AGV's cell), and the planner restarts from the
//     configuration executed;
//   - adg / adg-follow, the Driver's zone mutex (Driver::set_zones): a move into a zone
//     starts only while no other AGV stands in it for the ADG or runs a move into it; held
//     entrants are counted (count_held()) like admit()'s, so after kBlockAfter ticks the
//     zone leaves the planner's graph (a replan) until it empties. The mutex only delays
//     starts; the ADG's order and the dependency DAG are unchanged.
// Safety checks both independently on SUMO's poses (rule_check.hpp).
//
// Completeness: while cells or arcs are closed or zones occupied the planner is a fresh
// RT-LaCAM on a smaller directed graph per change, complete for the instance on that graph
// when every AGV's goal there (its real goal, or its waiting cell) is reachable
// (rt_lacam.hpp), with no guarantee across changes. A one-direction closure leaves the
// aisle's cells usable the other way, so the graph stays strongly connected unless that
// lane was the only way into or out of some cells (a two-way dead-end stub: its far cells
// can then be entered but not left, or left but not entered; the AGVs whose goals it cuts
// off wait, as for closed cells). A closure that ends and zones that empty restore the real
// graph and goals, and so RT-LaCAM's completeness from there (rt_lacam.hpp; under adg with
// the ADG's deadlock freedom, as after the last stuck replan). A zone that cuts the net into
// pieces is refused: an AGV parked in it would cut every route between them. With the zones
// in the planner (rules.plan_zones) no zone ever changes the graph or restarts the search:
// RT-LaCAM is complete over the steps that keep the zones (planner/zones.hpp), from the last
// closure change on. The rotation solvers are complete on no graph (planner/rotation/rotation_dist.hpp), with rules or without.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "controller/config.hpp"
#include "gridify/cell_map.hpp"
#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace controller {

class SumoBackend;

struct Closure {
  std::string what;  // "rerouter 'r1' (file:line)" or "rules.closures[0]"
  std::vector<std::string> lanes;
  std::vector<planner::Vertex> cells;
  double begin = 0, end = 1e300;
};

struct Zone {
  std::string id, what;
  std::vector<planner::Vertex> cells;
};

class Rules {
 public:
  // From the config and sumo.additional; nullptr when there is nothing to keep (no closure,
  // no zone, no lanes to watch). Bad input throws ConfigError (one line naming the object):
  // an unknown lane or edge, end < begin, a zone with no cells or one that cuts the net, two
  // one-shot goals in one zone.
  // `goals`: one-shot goals (empty for lifelong), checked against every closure: one whose
  // cells close or cut off a goal is reported in `warnings` (the AGV will wait).
  // `starts`: no zone may hold two of them either.
  static std::unique_ptr<Rules> make(const Config& cfg, const gridify::CellMap& map, const planner::Config& starts,
                                     const planner::Config& goals, std::vector<std::string>& warnings);
  // The zones alone (their cells sorted), read as make() reads them, unchecked: random starts
  // and goals are drawn out of them before the run (fleet.hpp, keep_out_of_zones).
  static std::vector<Zone> zones_of(const Config& cfg, const gridify::CellMap& map);

  Rules(const gridify::CellMap& map, std::vector<Closure> closures, std::vector<Zone> zones);

 private:
  // The closures and zones of the YAML and (rules.sumo) sumo.additional; unknown names throw.
  static void read(const Config& cfg, const gridify::CellMap& map, std::vector<Closure>& closures, std::vector<Zone>& zones);

 public:

  // Closures or zones configured (else only lanes are watched: the planner stays as it is
  // until a watched lane closes).
  bool configured() const { return !closures_.empty() || !zones_.empty(); }
  // Lanes polled every tick for their permissions (none: watching off).
  void watch(std::vector<std::string> lanes) { watched_ = std::move(lanes); }
  // The tick boundary at time t: the closures active then, plus the watched lanes SUMO says
  // the AGVs may not use. true if the closed cells or the closed watched lanes changed.
  bool update(double t, SumoBackend* sumo);
  const std::vector<uint8_t>& closed() const { return closed_; }
  int num_closed() const { return num_closed_; }
  std::string closed_by(planner::Vertex v) const;  // what closes it ("" if open)
  // One-direction closures: the arcs u -> v closed now (one lane of a two-way aisle).
  using Arc = std::pair<planner::Vertex, planner::Vertex>;
  const std::vector<Arc>& closed_arcs() const { return closed_arcs_; }  // sorted
  bool arc_closed(planner::Vertex u, planner::Vertex v) const;
  std::string arc_closed_by(planner::Vertex u, planner::Vertex v) const;  // "" if open
  bool anything_closed() const { return num_closed_ > 0 || !closed_arcs_.empty(); }

  const std::vector<Zone>& zones() const { return zones_; }
  const std::vector<std::vector<int>>& zones_of() const { return zone_of_; }  // cell -> zone indices
  // Per zone: 1 if some AGV of `at` stands in it.
  std::vector<uint8_t> occupied(const planner::Config& at) const;
  // Per zone: 1 if the planner must route around it -- someone stands in it and an entrant
  // has been held at its entry for kBlockAfter ticks in a row (the occupant is parked, or
  // the planner keeps sending others in). Otherwise admit() alone keeps the zone: a fresh
  // planner per zone entry and exit cost 5x the throughput on the small lifelong demo.
  std::vector<uint8_t> blocked_zones(const planner::Config& at) const;
  static constexpr int kBlockAfter = 3;

  // The graph the planner plans on: closed cells blocked (if enforced), the `blocked` zones
  // without their entry arcs, and no arc out of a `frozen` cell (one entry per cell, or
  // empty). Frozen: an AGV whose SUMO lane is closed by its permissions (watched lanes) can
  // go nowhere -- SUMO refuses every route from a lane the vehicle's class may not use
  // ("No connection", measured on 1.15) -- so it waits on its cell, and the cells of such
  // lanes are no way out for anyone.
  planner::Graph graph(const std::vector<uint8_t>& blocked, bool closures, const std::vector<uint8_t>& frozen = {}) const;
  // Watched lanes closed at the last update, and their cells (interior, junctions closed).
  const std::vector<std::string>& lanes_closed() const { return lanes_closed_; }
  std::vector<uint8_t> frozen_cells(const planner::Config& at, const std::vector<std::string>& pose_lanes) const;

  // Goals each AGV can reach from `at` on `g`, the others waiting (above); `waiting[i]` is
  // set for those. `lines` receives one line per AGV whose waiting (for a closure) began.
  planner::Config goals(const planner::Graph& g, const planner::Config& at, const planner::Config& goals,
                        std::vector<uint8_t>& waiting, double t, std::vector<std::string>& lines);

  // Holds AGVs so that every zone has at most one AGV over `cur` and `next` together (the
  // one already inside, else the entrant that waited longest). Returns how many were held.
  int admit(const planner::Config& cur, planner::Config& next);
  // The same count under adg (the Driver's zone mutex does the holding): `gated` per agent,
  // the zone whose mutex held it this tick (-1: none), `at` where the ADG has them. Returns
  // how many were held.
  int count_held(const std::vector<int>& gated, const planner::Config& at);

 private:
  // Closed lanes -> the cells they close: the interior cells of an aisle all of whose lanes
  // are closed, and a junction cell whose every aisle lane is closed.
  std::vector<uint8_t> cells_of_lanes(const std::vector<std::string>& lanes) const;
  // Closed lanes -> the arcs they close: along a closed lane of a two-way aisle whose other
  // lane is open, from its first junction cell to its last.
  std::vector<Arc> arcs_of_lanes(const std::vector<std::string>& lanes) const;

  const gridify::CellMap& map_;
  std::vector<Closure> closures_;
  std::vector<Zone> zones_;
  std::vector<std::vector<int>> zone_of_;
  std::vector<std::string> watched_;
  std::vector<std::string> lanes_closed_;  // watched lanes closed at the last update
  std::vector<uint8_t> closed_;
  std::vector<int> closer_;  // cell -> closure index, -2: a watched lane, -1: open
  int num_closed_ = 0;
  std::vector<Arc> closed_arcs_;  // sorted
  std::vector<int> arc_closer_;   // per closed arc: closure index, -2: a watched lane
  std::vector<uint8_t> waiting_;          // agent -> waiting for a closure (for the lines)
  std::vector<long long> zone_wait_;      // agent -> ticks held at a zone entry
  std::vector<int> zone_held_;            // zone -> ticks in a row an entrant was held
};

}  // namespace controller
