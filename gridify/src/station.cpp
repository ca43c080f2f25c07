#include "gridify/station.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <set>

#include "gridify/cell_map.hpp"
#include "gridify/net_file.hpp"
#include "xml_source.hpp"

namespace gridify {

static const char* default_kind(const std::string& element)
{
  if (element == "parkingArea") return "parking";
  if (element == "busStop" || element == "containerStop") return "stop";
  if (element == "chargingStation") return "charging";
  return "poi";
}

static std::string find_lane(const NetFile& net, const std::string& lane, double* length)
{
  for (const NetEdge& e : net.edges)
    for (const NetLane& l : e.lanes)
      if (l.id == lane) {
        *length = l.length;
        return e.id;
      }
  return {};
}

void tag_stations(CellMap& map, const NetFile& net, const std::string& path)
{
  XmlSource src(path);
  pugi::xml_node root = src.doc().document_element();
  if (!root) throw planner::input_error(path, 0, "empty additional file");
  // SUMO refuses a second element of one kind with the same id ("Process Error" at load).
  std::set<std::pair<std::string, std::string>> seen;
  for (pugi::xml_node n : root.children()) {
    std::string element = n.name();
    bool on_lane_range = element == "parkingArea" || element == "busStop" || element == "containerStop" ||
                         element == "chargingStation";
    bool poi = element == "poi";
    if (!on_lane_range && !poi) continue;

    Station st;
    st.id = src.str(n, "id");
    if (!seen.insert({element, st.id}).second) throw src.error(n, "<" + element + " id='" + st.id + "'>: duplicate id");
    st.element = element;
    st.kind = default_kind(element);
    if (poi && n.attribute("type")) st.kind = src.str(n, "type");
    if (element == "chargingStation") {
      if (n.attribute("power")) st.power = src.num(n, "power");
      st.efficiency = src.num_or(n, "efficiency", 0.95);  // SUMO's default
      if (st.power < 0 && n.attribute("power")) throw src.error(n, "<chargingStation id='" + st.id + "'>: power must be >= 0");
      if (st.efficiency <= 0 || st.efficiency > 1)
        throw src.error(n, "<chargingStation id='" + st.id + "'>: efficiency must be in (0, 1]");
    }
    for (pugi::xml_node p : n.children("param"))
      if (std::string(p.attribute("key").value()) == "kind") st.kind = src.str(p, "value");

    if (on_lane_range || (poi && n.attribute("lane"))) {
      std::string lane = src.str(n, "lane");
      double length = 0;
      if (find_lane(net, lane, &length).empty())
        throw src.error(n, "<" + element + " id='" + st.id + "'>: lane '" + lane + "' is not in " + net.path);
      double pos;
      if (on_lane_range) {
        // SUMO defaults: startPos 0, endPos the lane length; negative values count from the end.
        double a = src.num_or(n, "startPos", 0.0), b = src.num_or(n, "endPos", length);
        if (a < 0) a += length;
        if (b < 0) b += length;
        pos = 0.5 * (a + b);
      } else {
        pos = src.num(n, "pos");
        if (pos < 0) pos += length;
      }
      if (pos < 0 || pos > length + 1e-9)
        throw src.error(n, "<" + element + " id='" + st.id + "'>: position " + std::to_string(pos) +
                               " is outside lane '" + lane + "' (length " + std::to_string(length) + ")");
      st.cell = map.locate(lane, pos);
      if (st.cell < 0) {
        map.dropped.push_back({"station", st.id, "<" + element + "> on lane '" + lane + "': the lane was dropped from the graph", {}, {}});
        continue;
      }
    } else {
      // Free-standing POI: the cell nearest its x, y.
      double x = src.num(n, "x"), y = src.num(n, "y");
      double best = std::numeric_limits<double>::infinity();
      for (planner::Vertex v = 0; v < static_cast<planner::Vertex>(map.cells.size()); ++v) {
        double d = std::hypot(map.cells[v].x - x, map.cells[v].y - y);
        if (d < best) best = d, st.cell = v;
      }
      if (st.cell < 0) continue;
    }
    map.cells[st.cell].stations.push_back(static_cast<int>(map.stations.size()));
    map.stations.push_back(std::move(st));
  }
}

}  // namespace gridify
