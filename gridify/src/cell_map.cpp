#include "gridify/cell_map.hpp"

#include <cmath>
#include <stdexcept>

namespace gridify {

int CellMap::num_junction_cells() const
{
  int n = 0;
  for (const Cell& c : cells) n += c.kind == CellKind::Junction;
  return n;
}

planner::Vertex CellMap::junction_cell(const std::string& id) const
{
  auto it = junction_cells.find(id);
  return it == junction_cells.end() ? -1 : it->second;
}

SumoPose CellMap::pose_entering(planner::Vertex from, planner::Vertex to) const
{
  if (from < 0 || to < 0 || from >= graph.size() || to >= graph.size() || !graph.adjacent(from, to))
    throw std::invalid_argument("pose_entering: cells " + std::to_string(from) + " and " + std::to_string(to) +
                                " are not adjacent");
  const Cell& t = cells[to];
  if (t.kind == CellKind::Aisle) {
    const Aisle& a = aisles[t.aisle];
    // `from` is the previous cell on the chain (towards A) when moving A->B.
    bool forward = a.cells[t.k - 1] == from;
    return t.poses[forward ? 0 : 1];
  }
  // Entering a junction: over the aisle that contains `from` (or links the two junctions).
  const Cell& f = cells[from];
  const Aisle* a = nullptr;
  if (f.kind == CellKind::Aisle) {
    a = &aisles[f.aisle];
  } else {
    for (const Aisle& x : aisles)
      if (x.cells.size() == 2 && ((x.cells[0] == from && x.cells[1] == to) || (x.cells[0] == to && x.cells[1] == from))) {
        a = &x;
        break;
      }
  }
  if (!a) throw std::invalid_argument("pose_entering: no aisle between cells");
  // Arriving at A means driving B->A.
  bool to_is_b = a->cells.back() == to;
  return to_is_b ? SumoPose{a->lane_ab, a->length_ab} : SumoPose{a->lane_ba, a->length_ba};
}

planner::Vertex CellMap::locate(const std::string& lane, double pos, double* offset) const
{
  auto it = lane_aisle.find(lane);
  if (it == lane_aisle.end()) return -1;
  const Aisle& a = aisles[it->second.first];
  // Offset from A along the aisle, then the nearest chain index 0..steps.
  double from_a = it->second.second ? pos : a.length_ba - pos;
  long k = std::lround(from_a / a.spacing);
  if (k < 0) k = 0;
  if (k > a.steps) k = a.steps;
  planner::Vertex v = a.cells[k];
  if (offset) *offset = std::fabs(from_a - k * a.spacing);
  return v;
}

}  // namespace gridify
