#include "gridify/net_file.hpp"

#include <cstring>

#include "xml_source.hpp"

namespace gridify {

static bool is_internal_id(const std::string& id) { return !id.empty() && id[0] == ':'; }

// SUMO's lane permissions for vClass passenger (the AGVs'): allow, else disallow, else all.
static bool allows_agvs(const XmlSource& src, const pugi::xml_node& l)
{
  if (l.attribute("allow")) return lists_agv_class(src.str(l, "allow"));
  if (l.attribute("disallow")) return !lists_agv_class(src.str(l, "disallow"));
  return true;
}

NetFile NetFile::read(const std::string& path)
{
  XmlSource src(path);
  pugi::xml_node net = src.doc().child("net");
  if (!net) throw planner::input_error(path, 0, "no <net> root element (not a SUMO .net.xml)");

  NetFile nf;
  nf.path = path;
  for (pugi::xml_node n : net.children()) {
    const char* tag = n.name();
    if (!std::strcmp(tag, "edge")) {
      std::string id = src.str(n, "id");
      std::string function = src.str_or(n, "function", "normal");
      if (function == "internal" || is_internal_id(id)) {
        if (nf.internal_example.empty()) nf.internal_example = id;
        continue;
      }
      if (function != "normal") continue;  // crossing, walkingarea: pedestrians only
      NetEdge e;
      e.id = id;
      e.from = src.str(n, "from");
      e.to = src.str(n, "to");
      e.line = src.line(n);
      for (pugi::xml_node l : n.children("lane")) {
        NetLane lane;
        lane.id = src.str(l, "id");
        lane.index = src.integer(l, "index");
        lane.length = src.num(l, "length");
        lane.width = src.num_or(l, "width", 3.2);  // SUMO's default lane width
        lane.speed = src.num_or(l, "speed", 13.89);  // SUMO's default speed limit
        lane.agvs_allowed = allows_agvs(src, l);
        if (!(lane.speed > 0)) throw src.error(l, "lane '" + lane.id + "': speed must be positive");
        if (!(lane.length > 0)) throw src.error(l, "lane '" + lane.id + "': length must be positive");
        e.lanes.push_back(std::move(lane));
      }
      if (e.lanes.empty()) throw src.error(n, "edge '" + id + "' has no <lane>");
      if (!nf.edge_index.emplace(id, static_cast<int>(nf.edges.size())).second)
        throw src.error(n, "duplicate edge id '" + id + "'");
      nf.edges.push_back(std::move(e));
    } else if (!std::strcmp(tag, "junction")) {
      std::string id = src.str(n, "id");
      std::string type = src.str_or(n, "type", "");
      if (type == "internal" || is_internal_id(id)) continue;
      NetJunction j{id, type, src.num(n, "x"), src.num(n, "y"), src.line(n)};
      if (!nf.junction_index.emplace(id, static_cast<int>(nf.junctions.size())).second)
        throw src.error(n, "duplicate junction id '" + id + "'");
      nf.junctions.push_back(std::move(j));
    } else if (!std::strcmp(tag, "connection")) {
      std::string from = src.str(n, "from"), to = src.str(n, "to");
      std::string via = src.str_or(n, "via", "");
      if (!via.empty() && nf.internal_example.empty()) nf.internal_example = via;
      if (is_internal_id(from) || is_internal_id(to)) continue;
      nf.connections.push_back({from, to, src.integer(n, "fromLane"), src.integer(n, "toLane"), src.str_or(n, "dir", "")});
    }
  }
  // Edges may precede junctions in the file, so check references afterwards.
  for (const NetEdge& e : nf.edges) {
    for (const std::string* j : {&e.from, &e.to})
      if (!nf.junction_index.count(*j))
        throw planner::input_error(path, e.line, "edge '" + e.id + "' refers to unknown junction '" + *j + "'");
  }
  return nf;
}

const NetJunction* NetFile::junction(const std::string& id) const
{
  auto it = junction_index.find(id);
  return it == junction_index.end() ? nullptr : &junctions[it->second];
}

const NetEdge* NetFile::edge(const std::string& id) const
{
  auto it = edge_index.find(id);
  return it == edge_index.end() ? nullptr : &edges[it->second];
}

}  // namespace gridify
