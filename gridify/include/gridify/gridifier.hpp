#pragma once
// gridify(): SUMO warehouse net (.net.xml) -> CellMap (planner graph + cell <-> SUMO poses).
//
// Steps, each one small and explicit:
//  1. read the net (NetFile); refuse nets with internal links (their lane lengths exclude
//     the junction areas, so cells would not be evenly spaced);
//  2. pair opposite edges into aisles (one-way edges: error, or dropped on request);
//  3. cut each aisle into n = length / cell_length steps (not a multiple: error, or
//     snapped to n = round(length / cell_length) steps of length / n);
//  4. one cell per junction, n-1 cells inside each aisle; graph edges between consecutive
//     cells; a junction <-> aisle link only where SUMO lets a vehicle drive into the aisle
//     from that junction and out of the aisle into some kept edge (a vehicle parked on a
//     junction cell must be able to leave it again);
//  5. keep the largest connected component, listing what was dropped;
//  6. tag stations from an additional file (optional).
#include <string>

#include "gridify/cell_map.hpp"
#include "gridify/net_file.hpp"

namespace gridify {

// Most cells gridify() makes. More means a wrong cell_length or a corrupt lane length
// (a 1e9 m lane would be a billion cells); the largest shipped net has under 5000.
constexpr int kMaxCells = 1000000;

struct GridifyOptions {
  double cell_length = 1.0;  // metres between cell centres along an aisle
  double tolerance = 0.01;   // metres; SUMO writes lengths with 2 decimals
  bool snap = false;         // stretch aisles whose length is not a multiple of cell_length
  bool drop_one_way = false; // drop edges without an opposite edge instead of failing
  bool keep_largest = true;  // drop smaller components (false: a disconnected net is an error)
  std::string additional;    // SUMO additional file with stations ("" = none)
};

CellMap gridify(const NetFile& net, const GridifyOptions& opt = {});
CellMap gridify(const std::string& net_path, const GridifyOptions& opt = {});

}  // namespace gridify
