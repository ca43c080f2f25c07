#pragma once
// CellMap: the result of gridification. The planner graph plus, for every cell, where it
// is in SUMO, so the controller can command vehicles cell by cell.
//
// Vertex v of `graph` is `cells[v]`. Two kinds of cell:
//  - junction cell: one per kept SUMO junction (node), displayed at the junction centre.
//    A vehicle "at" junction J has its front at the end of the lane it came in on, so the
//    pose depends on the incoming edge E: (E_0, length of E_0). `poses` has one entry per
//    kept incoming edge; `movements` lists the SUMO connections between kept edges at J.
//  - aisle cell: interior cell k (1..n-1) of an aisle; poses[0] heads A->B
//    (ab lane, k*spacing), poses[1] heads B->A (ba lane, length_ba - k*spacing).
//    Displayed at A + (B-A)*k/n between the junction centres (never on lane shapes).
#include <string>
#include <unordered_map>
#include <vector>

#include "gridify/aisle.hpp"
#include "gridify/dropped.hpp"
#include "gridify/station.hpp"
#include "planner/graph.hpp"

namespace gridify {

enum class CellKind { Junction, Aisle };

struct SumoPose {
  std::string lane;
  double pos = 0;  // lane position of the vehicle front, in [0, lane length]
};

// A SUMO connection at a junction between two kept edges (lane 0 to lane 0).
struct Movement {
  std::string from, to;  // edge ids
  std::string dir;       // s, l, r, t, ...
};

struct Cell {
  CellKind kind = CellKind::Aisle;
  double x = 0, y = 0;
  std::string junction;  // junction cells: the junction id
  int aisle = -1;        // aisle cells: index into CellMap::aisles
  int k = 0;             // aisle cells: 1..steps-1
  std::vector<SumoPose> poses;
  std::vector<Movement> movements;  // junction cells only
  std::vector<int> stations;        // indices into CellMap::stations
};

struct CellMap {
  std::string net_path;
  double cell_length = 1.0;
  planner::Graph graph;
  std::vector<Cell> cells;
  std::vector<Aisle> aisles;      // kept aisles; Aisle::cells hold vertices of `graph`
  std::vector<Station> stations;  // tagged stations (on kept cells)
  std::vector<Dropped> dropped;
  std::vector<std::string> warnings;

  int num_junction_cells() const;
  int num_aisle_cells() const { return static_cast<int>(cells.size()) - num_junction_cells(); }

  // The junction cell of junction `id`, or -1 (unknown or dropped).
  planner::Vertex junction_cell(const std::string& id) const;

  // The SUMO pose to command for a vehicle moving from cell `from` to the adjacent cell
  // `to` (the pose at `to`, heading away from `from`). Throws std::invalid_argument if the
  // cells are not adjacent.
  SumoPose pose_entering(planner::Vertex from, planner::Vertex to) const;

  // The cell whose pose on `lane` is nearest to `pos`, or -1 if the lane is not on a kept
  // aisle. `*offset` (optional) receives |pos - pose of that cell|.
  planner::Vertex locate(const std::string& lane, double pos, double* offset = nullptr) const;

  // Filled by gridify(): lane id -> (aisle index, true if it is the ab lane).
  std::unordered_map<std::string, std::pair<int, bool>> lane_aisle;
  std::unordered_map<std::string, planner::Vertex> junction_cells;
};

}  // namespace gridify
