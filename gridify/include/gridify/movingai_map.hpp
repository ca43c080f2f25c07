#pragma once
// MovingAI .map export, for nets that are axis-aligned grids: every kept aisle is
// horizontal or vertical with spacing == cell_length, every cell sits on the lattice
// of step cell_length, and the graph is exactly the 4-neighbour graph of the occupied
// lattice points (two parallel aisles one cell apart would add moves the SUMO net does
// not have, so such a net is refused). Then rtlacam-bench can run on the same graph.
//
// Lattice coordinates: column = (x - min x) / cell_length, row = (max y - y) / cell_length
// (SUMO's y points up, MovingAI rows go down).
#include <string>
#include <vector>

#include "gridify/cell_map.hpp"

namespace gridify {

struct GridCoord {
  int col = 0, row = 0;
};

struct GridLayout {
  int width = 0, height = 0;
  std::vector<GridCoord> coord;  // per cell
};

// The layout, or an empty layout (width 0) with the reason in *why.
GridLayout grid_layout(const CellMap& map, std::string* why = nullptr);

// Writes the .map ('.' = cell, '@' = no cell); throws planner::InputError naming the
// reason when the net is not an axis-aligned grid, has one-way aisles (a .map cannot say
// so: every move would become two-way) or the file cannot be written. grid_layout()
// itself accepts one-way aisles (lattice neighbours joined one way are still joined).
void write_movingai_map(const CellMap& map, const std::string& path);

}  // namespace gridify
