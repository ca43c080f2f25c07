#include "gridify/json_writer.hpp"

#include <fstream>

#include "gridify/movingai_map.hpp"
#include "planner/error.hpp"
#include "planner/output_file.hpp"

namespace gridify {

nlohmann::json summary_json(const CellMap& m)
{
  int snapped = 0;
  for (const Aisle& a : m.aisles) snapped += a.snapped;
  return {{"junctions", m.num_junction_cells()}, {"aisles", m.aisles.size()},       {"cells", m.cells.size()},
          {"aisle_cells", m.num_aisle_cells()},  {"edges", m.graph.num_edges()},     {"max_degree", m.graph.max_degree()},
          {"snapped_aisles", snapped},           {"stations", m.stations.size()},    {"dropped", m.dropped.size()},
          {"one_way_arcs", m.graph.num_one_way()}};
}

nlohmann::json to_json(const CellMap& m)
{
  using nlohmann::json;
  GridLayout grid = grid_layout(m);
  json cells = json::array();
  for (planner::Vertex v = 0; v < static_cast<planner::Vertex>(m.cells.size()); ++v) {
    const Cell& c = m.cells[v];
    json j = {{"id", v}, {"kind", c.kind == CellKind::Junction ? "junction" : "aisle"}, {"x", c.x}, {"y", c.y}};
    if (c.kind == CellKind::Junction) {
      j["junction"] = c.junction;
      json mv = json::array();
      for (const Movement& x : c.movements) mv.push_back({{"from", x.from}, {"to", x.to}, {"dir", x.dir}});
      j["movements"] = mv;
    } else {
      j["aisle"] = c.aisle;
      j["k"] = c.k;
    }
    json poses = json::array();
    for (const SumoPose& p : c.poses) poses.push_back({{"lane", p.lane}, {"pos", p.pos}});
    j["poses"] = poses;
    if (!c.stations.empty()) {
      json st = json::array();
      for (int s : c.stations) st.push_back(m.stations[s].id);
      j["stations"] = st;
    }
    if (grid.width > 0) j["col"] = grid.coord[v].col, j["row"] = grid.coord[v].row;
    cells.push_back(std::move(j));
  }
  json edges = json::array(), arcs = json::array();  // two-way edges once; one-way arcs apart
  for (planner::Vertex v = 0; v < m.graph.size(); ++v)
    for (planner::Vertex u : m.graph.neighbors(v)) {
      if (!m.graph.adjacent(u, v)) arcs.push_back({v, u});
      else if (v < u) edges.push_back({v, u});
    }
  json aisles = json::array();
  for (const Aisle& a : m.aisles)
    aisles.push_back({{"ab", a.ab},           {"ba", a.ba},       {"lane_ab", a.lane_ab}, {"lane_ba", a.lane_ba},
                      {"a", a.a},             {"b", a.b},         {"length", a.length_ab}, {"steps", a.steps},
                      {"spacing", a.spacing}, {"snapped", a.snapped}, {"one_way", a.one_way}, {"cells", a.cells}});
  json stations = json::array();
  for (const Station& s : m.stations)
    stations.push_back({{"id", s.id}, {"kind", s.kind}, {"element", s.element}, {"cell", s.cell}});
  json dropped = json::array();
  for (const Dropped& d : m.dropped) dropped.push_back({{"kind", d.kind}, {"id", d.id}, {"reason", d.reason}});
  json out = {{"net", m.net_path}, {"cell_length", m.cell_length}, {"summary", summary_json(m)},
              {"cells", cells},    {"edges", edges}, {"one_way", arcs},             {"aisles", aisles},
              {"stations", stations}, {"dropped", dropped},        {"warnings", m.warnings}};
  if (grid.width > 0) out["grid"] = {{"width", grid.width}, {"height", grid.height}};
  return out;
}

void write_json(const CellMap& m, const std::string& path)
{
  planner::write_file(path, to_json(m).dump(1) + '\n');
}

}  // namespace gridify
