#pragma once
// NetFile: the parts of a SUMO .net.xml that gridify needs, as plain structs.
// Read with pugixml; no SUMO runtime. Internal edges/junctions (function="internal",
// ids starting with ':', type="internal") are skipped, but their presence is recorded:
// a net built with internal links has lane lengths that exclude the junction areas,
// which breaks the "lane length == node distance" model (see gridify/README.md).
#include <string>
#include <unordered_map>
#include <vector>

namespace gridify {

struct NetJunction {
  std::string id;
  std::string type;
  double x = 0, y = 0;
  int line = 0;  // in the .net.xml, for messages
};

struct NetLane {
  std::string id;
  int index = 0;
  double length = 0;
  double width = 0;
  double speed = 0;  // m/s, the lane's speed limit (SUMO's default 13.89 when absent)
  // The lane's allow / disallow let the AGVs' vehicle class (passenger, the default of the
  // controller's vType) drive it: false for a sidewalk or an aisle closed to vehicles.
  bool agvs_allowed = true;
};

struct NetEdge {
  std::string id;
  std::string from, to;  // junction ids
  std::vector<NetLane> lanes;
  int line = 0;
};

struct NetConnection {
  std::string from, to;  // edge ids
  int from_lane = 0, to_lane = 0;
  std::string dir;       // s, l, r, t, L, R, invalid
};

struct NetFile {
  std::string path;
  std::vector<NetJunction> junctions;
  std::vector<NetEdge> edges;            // normal edges only, file order
  std::vector<NetConnection> connections;  // between normal edges only
  std::unordered_map<std::string, int> junction_index;  // id -> index in junctions
  std::unordered_map<std::string, int> edge_index;      // id -> index in edges

  // First internal lane/edge seen (empty if none): the net was built with internal links.
  std::string internal_example;

  // Parses `path`. Throws planner::InputError "path:line: what" on a missing file,
  // malformed XML, missing/non-numeric attributes, duplicate ids or edges naming unknown
  // junctions.
  static NetFile read(const std::string& path);

  const NetJunction* junction(const std::string& id) const;
  const NetEdge* edge(const std::string& id) const;
};

}  // namespace gridify
