#include "gridify/aisle.hpp"

#include <map>

#include "planner/error.hpp"

namespace gridify {

static planner::Point centre(const NetFile& net, const std::string& j)
{
  const NetJunction* p = net.junction(j);
  return {p->x, p->y};
}

std::vector<Aisle> pair_aisles(const NetFile& net, bool drop_one_way, std::vector<Dropped>& dropped)
{
  // Lane index 0 (rightmost): warehouse aisles have one lane per direction.
  auto lane0 = [&](const NetEdge& edge) -> const NetLane& {
    for (const NetLane& l : edge.lanes)
      if (l.index == 0) return l;
    throw planner::input_error(net.path, edge.line, "edge '" + edge.id + "' has no lane with index 0");
  };
  // Edges whose lane 0 the AGVs may not drive (allow / disallow without passenger) are left
  // out, said so: an aisle closed to vehicles, or a sidewalk. Kept, the AGVs were routed onto
  // them and SUMO refused the route or the insertion mid-run.
  std::vector<char> closed(net.edges.size(), 0);
  // (from, to) -> edge index. std::map keeps the pairing independent of hash order.
  std::map<std::pair<std::string, std::string>, int> directed;
  for (int i = 0; i < static_cast<int>(net.edges.size()); ++i) {
    const NetEdge& e = net.edges[i];
    if (e.from == e.to)
      throw planner::input_error(net.path, e.line, "edge '" + e.id + "' starts and ends at junction '" + e.from + "'");
    if (!lane0(e).agvs_allowed) {
      closed[i] = 1;
      std::string why = "lane '" + lane0(e).id + "' does not allow vehicle class passenger (the AGVs')";
      for (const NetLane& l : e.lanes)
        if (l.index != 0 && l.agvs_allowed) {
          why += "; AGVs drive lane 0 only, and lane '" + l.id + "' allows them (a sidewalk? build the net without one)";
          break;
        }
      dropped.push_back({"closed edge", e.id, why, {{centre(net, e.from), centre(net, e.to)}}, {}});
      continue;
    }
    auto [it, fresh] = directed.emplace(std::make_pair(e.from, e.to), i);
    if (!fresh)
      throw planner::input_error(net.path, e.line,
                                 "edges '" + net.edges[it->second].id + "' and '" + e.id + "' both go from '" + e.from +
                                     "' to '" + e.to + "' (one aisle per pair of junctions)");
  }

  std::vector<Aisle> aisles;
  // File order: the first edge of a pair seen becomes the aisle's A->B direction.
  for (size_t i = 0; i < net.edges.size(); ++i) {
    const NetEdge& e = net.edges[i];
    if (closed[i]) continue;
    Aisle a;
    a.ab = e.id;
    a.a = e.from;
    a.b = e.to;
    a.lane_ab = lane0(e).id;
    a.length_ab = lane0(e).length;
    a.speed_ab = lane0(e).speed;
    auto back = directed.find({e.to, e.from});
    if (back == directed.end()) {
      // A one-way aisle: kept as arcs A->B (a directed planner graph) unless asked to drop it.
      if (drop_one_way) {
        dropped.push_back({"one-way edge", e.id, "one-way aisle: no opposite edge from '" + e.to + "' to '" + e.from + "'",
                           {{centre(net, e.from), centre(net, e.to)}}, {}});
        continue;
      }
      a.one_way = true;
      a.length_ba = a.length_ab;  // the aisle's length (no B->A lane)
      aisles.push_back(std::move(a));
      continue;
    }
    const NetEdge& o = net.edges[back->second];
    if (net.edge_index.at(o.id) < net.edge_index.at(e.id)) continue;  // pair already made from `o`
    a.ba = o.id;
    a.lane_ba = lane0(o).id;
    a.length_ba = lane0(o).length;
    a.speed_ba = lane0(o).speed;
    aisles.push_back(std::move(a));
  }
  return aisles;
}

}  // namespace gridify
