#pragma once
// Dropped: something of the SUMO net that gridify left out of the graph, and why.
// Gridify never drops silently: every one-way edge removed on request, every edge whose
// lane 0 the AGVs may not drive, every small
// component, every junction<->aisle link without a SUMO connection and every station
// that landed on a removed part is listed here, printed by the CLI and drawn in the SVG.
#include <string>
#include <vector>

#include "planner/graph.hpp"

namespace gridify {

struct Dropped {
  std::string kind;    // "one-way edge", "closed edge", "component", "link", "station"
  std::string id;      // edge id, junction ids, "junction/edge", station id
  std::string reason;  // one line
  // Display geometry (junction centre to junction centre) so the SVG can show it.
  std::vector<std::pair<planner::Point, planner::Point>> segments;
  // Every junction and edge id it took with it (a component; `id` shows only a few), so a
  // config naming one of them can say that gridify dropped it.
  std::vector<std::string> members;
};

}  // namespace gridify
