#pragma once
// JSON dump of a CellMap, for the controller, scripts and people:
//   { net, cell_length, summary{...},
//     cells:   [{id, kind, x, y, junction | aisle+k, poses:[{lane,pos}], movements, stations, col,row?}],
//     edges:   [[u, v], ...]  (two-way, u < v),
//     one_way: [[u, v], ...]  (arcs u -> v without the reverse: one-way aisles),
//     aisles:  [{ab, ba, lane_ab, lane_ba, a, b, length, steps, spacing, snapped, one_way, cells}],
//              (a one-way aisle has ba = lane_ba = "")
//     stations:[{id, kind, element, cell}], dropped: [{kind, id, reason}], warnings: [...] }
// col/row are present when the net is an axis-aligned grid (see movingai_map.hpp).
#include <nlohmann/json.hpp>
#include <string>

#include "gridify/cell_map.hpp"

namespace gridify {

nlohmann::json summary_json(const CellMap& map);
nlohmann::json to_json(const CellMap& map);
void write_json(const CellMap& map, const std::string& path);

}  // namespace gridify
