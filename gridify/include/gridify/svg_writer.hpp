#pragma once
// SVG picture of a gridification, for a person to check it at a glance:
//  - aisles as grey bands between junction centres (where cells live, not SUMO's
//    shortened lane shapes), junctions as grey squares;
//  - graph edges as thin dark lines, aisle cells as dots, junction cells as blue squares;
//  - stations as coloured discs with their id (colour by kind, legend at the top);
//  - dropped parts (one-way edges, small components, links) as dashed red lines,
//    dropped junctions as red hollow squares.
#include <string>

#include "gridify/cell_map.hpp"

namespace gridify {

struct SvgOptions {
  double pixels_per_metre = 0;  // 0: chosen so the picture is about 1000 px wide or high
  bool labels = true;           // junction ids and station ids
};

std::string to_svg(const CellMap& map, const SvgOptions& opt = {});
void write_svg(const CellMap& map, const std::string& path, const SvgOptions& opt = {});

}  // namespace gridify
