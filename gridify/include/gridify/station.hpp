#pragma once
// Station: a named place tasks can refer to (pick-up, drop, parking, charging), taken
// from SUMO objects in an additional file and snapped to the nearest cell:
//  - <parkingArea>, <busStop>, <containerStop>, <chargingStation> with lane, startPos,
//    endPos: the cell nearest the middle of [startPos, endPos] on that lane;
//  - <poi> with lane and pos: likewise; <poi> with x, y: the cell nearest (x, y).
// The kind is a child <param key="kind" value="..."/> if present, else a poi's `type`,
// else the element's default (parkingArea: parking, busStop/containerStop: stop,
// chargingStation: charging, poi: poi).
#include <string>

#include "planner/graph.hpp"

namespace gridify {

struct Station {
  std::string id;
  std::string kind;
  std::string element;  // parkingArea, busStop, ...
  planner::Vertex cell = -1;
  // chargingStation: its `power` (W) and `efficiency` as SUMO reads them; power -1 when the
  // attribute is absent (the run then uses fleet.battery.charge_w).
  double power = -1, efficiency = 1;
};

struct CellMap;
struct NetFile;

// Reads `path` and tags cells of `map`, built from `net` (fills map.stations and
// Cell::stations). Stations on lanes of `net` that gridify dropped are listed in
// map.dropped; lanes unknown to `net`, missing or non-numeric attributes and malformed XML
// throw planner::InputError "path:line: what".
void tag_stations(CellMap& map, const NetFile& net, const std::string& path);

}  // namespace gridify
