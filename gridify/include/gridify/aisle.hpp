#pragma once
// Aisle: one physical warehouse aisle between junctions A and B. A two-way aisle is a pair
// of opposite single-lane SUMO edges A->B ("ab") and B->A ("ba"). SUMO 1.15 has no shared
// two-way lane for vehicles, so the two lanes lie +-width/2 off the centreline; gridify
// treats them as one aisle with one row of cells (see gridify/README.md). A one-way aisle
// is a single edge A->B with no opposite edge (`one_way`; ba, lane_ba empty): its cells
// are joined by arcs A->B only, so the planner graph is directed.
//
// Cells along an aisle live in lane-position space: with n steps of `spacing`, aisle
// cell k (1..n-1) is at offset k*spacing from A, i.e. at (ab lane, k*spacing) heading
// A->B and at (ba lane, length_ba - k*spacing) heading B->A. The junction cells A and B
// close the chain.
#include <string>
#include <vector>

#include "gridify/dropped.hpp"
#include "gridify/net_file.hpp"
#include "planner/graph.hpp"

namespace gridify {

struct Aisle {
  std::string ab, ba;            // edge ids
  std::string lane_ab, lane_ba;  // lane index 0 of each edge: the lanes AGVs are commanded on
  std::string a, b;              // junction ids
  double length_ab = 0, length_ba = 0;  // lane lengths (equal within tolerance)
  double speed_ab = 0, speed_ba = 0;    // lane speed limits, m/s (the Driver keeps to them)
  int steps = 0;                 // n: the aisle has n-1 interior cells and n graph edges
  double spacing = 0;            // cell_length, or length_ab / n when snapped
  bool snapped = false;
  bool one_way = false;          // no B->A edge: moves go A->B only
  std::vector<planner::Vertex> cells;  // A's junction cell, interior cells 1..n-1, B's junction cell
};

// Pairs the normal edges of `net` into aisles (no cells yet: steps/spacing/cells unset).
// An edge without an opposite edge is a one-way aisle (Aisle::one_way), or, with
// `drop_one_way`, it is left out and listed in `dropped`. Two edges in the same direction
// between the same junctions, and self-loops, are errors.
std::vector<Aisle> pair_aisles(const NetFile& net, bool drop_one_way, std::vector<Dropped>& dropped);

}  // namespace gridify
