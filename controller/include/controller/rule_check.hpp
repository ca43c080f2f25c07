#pragma once
// RuleCheck: the traffic rules (rules.hpp) checked after every SUMO step from SUMO's own
// poses, not from the plan -- the Safety side of the rules, independent of how the
// controller keeps them (the planner's graph, the zone admission):
//   - no AGV enters a closed cell: the cell nearest an AGV's front (CellMap::locate) is
//     closed now and the cell it was nearest at the previous check was open (an AGV on a
//     cell when it closes may stay there or leave through closed cells). Under adg an AGV
//     may be driving when a closure begins, and a moving AGV cannot stop on a cell
//     boundary: the targets of its moves then in progress count as its cells (excuse());
//     the excuse ends when it leaves them;
//   - no AGV drives along an arc closed one way (one lane of a two-way aisle closed): the
//     cell nearest its front changes from u to v with u -> v closed (excuse() as above);
//   - no one-at-a-time zone holds two AGVs: at most one front is nearest a cell of a zone.
// A violation is a ControlError (like every Safety violation: exit 3, metrics.json error)
// naming the AGVs, the cell or zone, what closed it and the time.
#include <string>
#include <vector>

#include "controller/rules.hpp"
#include "controller/sumo_backend.hpp"
#include "gridify/cell_map.hpp"

namespace controller {

class RuleCheck {
 public:
  RuleCheck(const gridify::CellMap& map, const Rules& rules) : map_(map), rules_(rules) {}
  void check(const std::vector<VehiclePose>& poses, const std::vector<std::string>& ids, double t);
  long long checks() const { return checks_; }
  // Agent i was driving into `cells` when the closed set changed (adg; replaces earlier ones).
  void excuse(int i, std::vector<planner::Vertex> cells);

 private:
  const gridify::CellMap& map_;
  const Rules& rules_;
  std::vector<planner::Vertex> last_;  // cell nearest each front at the previous check
  long long checks_ = 0;
  std::vector<std::vector<planner::Vertex>> excused_;  // per agent (excuse())
};

}  // namespace controller
