#include "controller/rules.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <unordered_map>
#include <unordered_set>

#include "controller/commander.hpp"
#include "controller/fleet.hpp"
#include "controller/sumo_backend.hpp"
#include "gridify/rules_file.hpp"
#include "planner/blocked.hpp"
#include "planner/error.hpp"

namespace controller {

namespace {

// The AGVs' SUMO vehicle class: the controller's vType sets none, so SUMO's default.
constexpr const char* kAgvClass = "passenger";

std::string fmt_s(double s)
{
  if (s >= 1e299) return "the end";
  char b[32];
  std::snprintf(b, sizeof b, "%g s", s);
  return b;
}

bool dropped(const gridify::CellMap& map, const std::string& name)
{
  for (const gridify::Dropped& d : map.dropped) {
    if (d.id == name) return true;
    for (const std::string& m : d.members)
      if (m == name) return true;
  }
  return false;
}

// The lane AGVs use on `edge`, "" if gridify has no aisle for it.
std::string lane_of_edge(const gridify::CellMap& map, const std::string& edge)
{
  for (const gridify::Aisle& a : map.aisles) {
    if (a.ab == edge) return a.lane_ab;
    if (!a.ba.empty() && a.ba == edge) return a.lane_ba;
  }
  return "";
}

}  // namespace

void Rules::read(const Config& cfg, const gridify::CellMap& map, std::vector<Closure>& closures, std::vector<Zone>& zones)
{
  auto fail = [&](const std::string& key, const std::string& what) { throw ConfigError(cfg.path + ": " + key + ": " + what); };
  // Lanes and edges by id: a name gridify dropped (a one-way edge with drop_one_way, a
  // cut-off component) closes nothing the AGVs use; any other unknown name is an error.
  auto add_lane = [&](const std::string& key, const std::string& lane, std::vector<std::string>& out) {
    if (map.lane_aisle.count(lane)) return out.push_back(lane);
    if (dropped(map, lane.substr(0, lane.rfind('_')))) return;
    fail(key, "unknown lane '" + lane + "' (not a lane of the gridified net " + cfg.sumo.net + ")");
  };
  auto add_edge = [&](const std::string& key, const std::string& edge, std::vector<std::string>& out) {
    const std::string lane = lane_of_edge(map, edge);
    if (!lane.empty()) return out.push_back(lane);
    if (dropped(map, edge)) return;
    fail(key, "unknown edge '" + edge + "' (not an edge of the gridified net " + cfg.sumo.net + ")");
  };

  for (const RuleClosure& rc : cfg.rules.closures) {
    Closure c;
    c.what = rc.key;
    c.begin = rc.begin;
    c.end = rc.end;
    for (const std::string& l : rc.lanes) add_lane(rc.key + ".lanes", l, c.lanes);
    for (const std::string& e : rc.edges) add_edge(rc.key + ".edges", e, c.lanes);
    for (const CellRef& ref : rc.cells) c.cells.push_back(resolve_cell(cfg, map, ref));
    closures.push_back(std::move(c));
  }
  std::vector<planner::Vertex> interior;
  auto aisle_cells = [&](const std::vector<std::string>& lanes) {
    std::vector<planner::Vertex> out;
    for (const std::string& l : lanes) {
      const gridify::Aisle& a = map.aisles[map.lane_aisle.at(l).first];
      out.insert(out.end(), a.cells.begin() + 1, a.cells.end() - 1);
    }
    return out;
  };
  for (const RuleZone& rz : cfg.rules.zones) {
    Zone z;
    z.id = rz.id;
    z.what = rz.key + " ('" + rz.id + "')";
    std::vector<std::string> lanes;
    for (const std::string& l : rz.lanes) add_lane(rz.key + ".lanes", l, lanes);
    for (const std::string& e : rz.edges) add_edge(rz.key + ".edges", e, lanes);
    z.cells = aisle_cells(lanes);
    for (const CellRef& ref : rz.cells) z.cells.push_back(resolve_cell(cfg, map, ref));
    zones.push_back(std::move(z));
  }
  if (cfg.rules.sumo && !cfg.sumo.additional.empty()) {
    gridify::SumoRules sr;
    try {
      sr = gridify::read_sumo_rules(cfg.sumo.additional);
    } catch (const planner::InputError& e) {
      fail("sumo.additional", e.what());
    }
    for (const gridify::SumoClosure& sc : sr.closures) {
      Closure c;
      c.what = sc.source;
      c.begin = sc.begin;
      c.end = sc.end;
      for (const std::string& e : sc.edges) add_edge("sumo.additional: " + sc.source + ": closingReroute", e, c.lanes);
      for (const std::string& l : sc.lanes) add_lane("sumo.additional: " + sc.source + ": closingLaneReroute", l, c.lanes);
      closures.push_back(std::move(c));
    }
    for (const gridify::SumoZone& sz : sr.zones) {
      Zone z;
      z.id = sz.id;
      z.what = sz.source;
      for (planner::Vertex v = 0; v < static_cast<planner::Vertex>(map.cells.size()); ++v)
        if (gridify::inside(sz.shape, map.cells[v].x, map.cells[v].y)) z.cells.push_back(v);
      zones.push_back(std::move(z));
    }
  }
  for (Zone& z : zones) {
    std::sort(z.cells.begin(), z.cells.end());
    z.cells.erase(std::unique(z.cells.begin(), z.cells.end()), z.cells.end());
  }
}

std::vector<Zone> Rules::zones_of(const Config& cfg, const gridify::CellMap& map)
{
  std::vector<Closure> closures;
  std::vector<Zone> zones;
  read(cfg, map, closures, zones);
  return zones;
}

std::unique_ptr<Rules> Rules::make(const Config& cfg, const gridify::CellMap& map, const planner::Config& starts,
                                   const planner::Config& goals, std::vector<std::string>& warnings)
{
  auto fail = [&](const std::string& key, const std::string& what) { throw ConfigError(cfg.path + ": " + key + ": " + what); };
  std::vector<Closure> closures;
  std::vector<Zone> zones;
  read(cfg, map, closures, zones);
  // By default (-1) lockstep runs on libsumo watch; adg runs only when asked (a poll of every
  // lane per tick is not free on a large net). Every solver: a rotation solver restarts on
  // the rules' graph from the AGVs' cells and headings (Run::rules_restart, Run::replan).
  const bool watch = cfg.rules.watch_lanes == 1 ||
                     (cfg.rules.watch_lanes < 0 && cfg.run.backend == "libsumo" && cfg.run.executor == "lockstep");

  // Zones: cells, not a cut, not two one-shot goals.
  const planner::Graph& g = map.graph;
  int pieces0 = 0;
  g.strong_components(&pieces0);
  for (Zone& z : zones) {
    if (z.cells.empty()) fail(z.what, "a zone with no cells (no cell of the gridified net lies in it)");
    std::vector<uint8_t> in(g.size(), 0);
    for (planner::Vertex v : z.cells) in[v] = 1;
    int pieces = 0;
    g.strong_components(&pieces, &in);
    if (pieces > pieces0)
      fail(z.what, "zone '" + z.id + "' cuts the net into " + std::to_string(pieces) +
                       " pieces (an AGV parked in it would cut every route between them)");
    for (const auto& [cells, what] : {std::make_pair(&goals, "goals"), std::make_pair(&starts, "starts")}) {
      std::vector<int> inside;
      for (size_t i = 0; i < cells->size(); ++i)
        if (in[(*cells)[i]]) inside.push_back(static_cast<int>(i));
      if (inside.size() > 1)
        fail(z.what, "zone '" + z.id + "' holds the " + what + " of " + Commander::vehicle_id(inside[0]) + " and " +
                         Commander::vehicle_id(inside[1]) + ": at most one AGV may be inside");
    }
  }
  if (closures.empty() && zones.empty() && !watch) return nullptr;
  auto rules = std::make_unique<Rules>(map, std::move(closures), std::move(zones));
  if (watch) {
    std::vector<std::string> lanes;
    for (const gridify::Aisle& a : map.aisles) {
      lanes.push_back(a.lane_ab);
      if (!a.lane_ba.empty()) lanes.push_back(a.lane_ba);
    }
    rules->watch(std::move(lanes));
  }
  // Closures that close or cut off a one-shot goal: named now, the AGV waits then.
  for (const Closure& c : rules->closures_) {
    std::vector<uint8_t> closed = rules->cells_of_lanes(c.lanes);
    for (planner::Vertex v : c.cells) closed[v] = 1;
    std::vector<Arc> arcs = rules->arcs_of_lanes(c.lanes);
    std::sort(arcs.begin(), arcs.end());
    const planner::Graph open = planner::without_arcs(
        g, [&](planner::Vertex u, planner::Vertex v) { return std::binary_search(arcs.begin(), arcs.end(), Arc{u, v}); });
    int n = 0;
    const std::vector<int> comp = open.strong_components(&n, &closed);
    std::vector<int> size(n, 0);
    for (int k : comp)
      if (k >= 0) ++size[k];
    const int main = n > 0 ? static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin()) : -1;
    for (size_t i = 0; i < goals.size(); ++i) {
      const planner::Vertex v = goals[i];
      if (closed[v] || comp[v] != main)
        warnings.push_back(c.what + " " + (closed[v] ? "closes" : "cuts off") + " the goal of " +
                           Commander::vehicle_id(static_cast<int>(i)) + " (cell " + std::to_string(v) + ") from " +
                           fmt_s(c.begin) + " to " + fmt_s(c.end) + ": it waits meanwhile");
    }
  }
  return rules;
}

Rules::Rules(const gridify::CellMap& map, std::vector<Closure> closures, std::vector<Zone> zones)
    : map_(map), closures_(std::move(closures)), zones_(std::move(zones))
{
  const int n = map.graph.size();
  zone_of_.assign(n, {});
  for (size_t z = 0; z < zones_.size(); ++z)
    for (planner::Vertex v : zones_[z].cells) zone_of_[v].push_back(static_cast<int>(z));
  closed_.assign(n, 0);
  closer_.assign(n, -1);
}

std::vector<uint8_t> Rules::cells_of_lanes(const std::vector<std::string>& lanes) const
{
  std::vector<uint8_t> closed(map_.graph.size(), 0);
  if (lanes.empty()) return closed;
  std::unordered_set<std::string> shut(lanes.begin(), lanes.end());
  for (const std::string& l : shut) {
    const gridify::Aisle& a = map_.aisles[map_.lane_aisle.at(l).first];
    // One lane of a two-way aisle: only its direction closes (arcs_of_lanes()).
    if (!shut.count(a.lane_ab) || (!a.lane_ba.empty() && !shut.count(a.lane_ba))) continue;
    for (size_t k = 1; k + 1 < a.cells.size(); ++k) closed[a.cells[k]] = 1;
  }
  // A junction cell closes with the last open aisle lane at it.
  std::unordered_map<std::string, bool> open_at;  // junction -> some aisle lane at it open
  for (const gridify::Aisle& a : map_.aisles) {
    bool open = !shut.count(a.lane_ab) || (!a.lane_ba.empty() && !shut.count(a.lane_ba));
    if (a.lane_ba.empty()) open = !shut.count(a.lane_ab);
    for (const std::string& j : {a.a, a.b}) open_at[j] = open_at[j] || open;
  }
  for (const auto& [j, open] : open_at)
    if (!open) {
      const planner::Vertex v = map_.junction_cell(j);
      if (v >= 0) closed[v] = 1;
    }
  return closed;
}

std::vector<Rules::Arc> Rules::arcs_of_lanes(const std::vector<std::string>& lanes) const
{
  std::vector<Arc> out;
  std::unordered_set<std::string> shut(lanes.begin(), lanes.end());
  for (const std::string& l : shut) {
    const gridify::Aisle& a = map_.aisles[map_.lane_aisle.at(l).first];
    if (a.lane_ba.empty() || (shut.count(a.lane_ab) && shut.count(a.lane_ba))) continue;  // cells close
    const bool ab = l == a.lane_ab;
    for (size_t k = 0; k + 1 < a.cells.size(); ++k)
      out.push_back(ab ? Arc{a.cells[k], a.cells[k + 1]} : Arc{a.cells[k + 1], a.cells[k]});
  }
  return out;
}

bool Rules::arc_closed(planner::Vertex u, planner::Vertex v) const
{
  return std::binary_search(closed_arcs_.begin(), closed_arcs_.end(), Arc{u, v});
}

std::string Rules::arc_closed_by(planner::Vertex u, planner::Vertex v) const
{
  const auto it = std::lower_bound(closed_arcs_.begin(), closed_arcs_.end(), Arc{u, v});
  if (it == closed_arcs_.end() || *it != Arc{u, v}) return "";
  const int c = arc_closer_[it - closed_arcs_.begin()];
  return c == -2 ? "a lane SUMO closed for the AGVs' class" : closures_[c].what;
}

bool Rules::update(double t, SumoBackend* sumo)
{
  std::vector<int> who(map_.graph.size(), -1);
  std::vector<std::pair<Arc, int>> arcs;  // one-direction closures: arc, closer
  for (size_t c = 0; c < closures_.size(); ++c) {
    const Closure& cl = closures_[c];
    if (t < cl.begin || t >= cl.end) continue;
    for (const Arc& a : arcs_of_lanes(cl.lanes)) arcs.push_back({a, static_cast<int>(c)});
    const std::vector<uint8_t> cells = cells_of_lanes(cl.lanes);
    for (planner::Vertex v = 0; v < static_cast<planner::Vertex>(cells.size()); ++v)
      if (cells[v] && who[v] < 0) who[v] = static_cast<int>(c);
    for (planner::Vertex v : cl.cells)
      if (who[v] < 0) who[v] = static_cast<int>(c);
  }
  const std::vector<std::string> lanes_before = std::move(lanes_closed_);
  lanes_closed_.clear();
  if (sumo)
    for (const std::string& l : watched_) {
      const std::vector<std::string> allowed = sumo->lane_allowed(l);
      const bool listed = std::find(allowed.begin(), allowed.end(), kAgvClass) != allowed.end();
      // Empty: every class may use it -- or none (closed to all): the disallowed list tells.
      if (allowed.empty()) {
        const std::vector<std::string> no = sumo->lane_disallowed(l);
        if (std::find(no.begin(), no.end(), kAgvClass) != no.end()) lanes_closed_.push_back(l);
      } else if (!listed) {
        lanes_closed_.push_back(l);
      }
    }
  if (!lanes_closed_.empty()) {
    for (const Arc& a : arcs_of_lanes(lanes_closed_)) arcs.push_back({a, -2});
    const std::vector<uint8_t> cells = cells_of_lanes(lanes_closed_);
    for (planner::Vertex v = 0; v < static_cast<planner::Vertex>(cells.size()); ++v)
      if (cells[v] && who[v] < 0) who[v] = -2;
  }
  bool changed = lanes_closed_ != lanes_before;  // (the routes must avoid the new set)
  // Closed arcs (first closer named); two closures of the same lane's two directions in
  // different closures leave both directions' arcs closed, the cells open: still no way in.
  std::stable_sort(arcs.begin(), arcs.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Arc> closed_arcs;
  std::vector<int> arc_closer;
  for (const auto& [a, c] : arcs)
    if (closed_arcs.empty() || closed_arcs.back() != a) closed_arcs.push_back(a), arc_closer.push_back(c);
  changed = changed || closed_arcs != closed_arcs_;
  closed_arcs_ = std::move(closed_arcs);
  arc_closer_ = std::move(arc_closer);
  num_closed_ = 0;
  for (size_t v = 0; v < who.size(); ++v) {
    const uint8_t c = who[v] != -1;
    changed = changed || c != closed_[v];
    closed_[v] = c;
    closer_[v] = who[v];
    num_closed_ += c;
  }
  return changed;
}

std::string Rules::closed_by(planner::Vertex v) const
{
  if (!closed_[v]) return "";
  if (closer_[v] == -2) return "a lane SUMO closed for the AGVs' class";
  return closures_[closer_[v]].what;
}

std::vector<uint8_t> Rules::occupied(const planner::Config& at) const
{
  std::vector<uint8_t> occ(zones_.size(), 0);
  for (planner::Vertex v : at)
    for (int z : zone_of_[v]) occ[z] = 1;
  return occ;
}

std::vector<uint8_t> Rules::blocked_zones(const planner::Config& at) const
{
  std::vector<uint8_t> b = occupied(at);
  for (size_t z = 0; z < b.size(); ++z) b[z] = b[z] && z < zone_held_.size() && zone_held_[z] >= kBlockAfter;
  return b;
}

std::vector<uint8_t> Rules::frozen_cells(const planner::Config& at, const std::vector<std::string>& pose_lanes) const
{
  std::vector<uint8_t> f = cells_of_lanes(lanes_closed_);
  for (size_t i = 0; i < at.size() && i < pose_lanes.size(); ++i)
    if (std::find(lanes_closed_.begin(), lanes_closed_.end(), pose_lanes[i]) != lanes_closed_.end()) f[at[i]] = 1;
  return f;
}

planner::Graph Rules::graph(const std::vector<uint8_t>& occupied, bool closures, const std::vector<uint8_t>& frozen) const
{
  const planner::Graph& g = map_.graph;
  const bool any_closed = closures && num_closed_ > 0;
  const bool any_arcs = closures && !closed_arcs_.empty();
  const bool any_occupied = std::find(occupied.begin(), occupied.end(), 1) != occupied.end();
  const bool any_frozen = closures && std::find(frozen.begin(), frozen.end(), 1) != frozen.end();
  auto none = [](planner::Vertex, planner::Vertex) { return false; };
  planner::Graph b = any_closed ? planner::blocked_graph(g, closed_) : planner::without_arcs(g, none);
  if (any_arcs) b = planner::without_arcs(b, [&](planner::Vertex u, planner::Vertex v) { return arc_closed(u, v); });
  if (any_frozen) b = planner::without_arcs(b, [&](planner::Vertex u, planner::Vertex) { return frozen[u] != 0; });
  if (!any_occupied) return b;
  // Into an occupied zone from outside it: nobody but its occupant may be in it.
  return planner::without_arcs(b, [&](planner::Vertex u, planner::Vertex v) {
    for (int z : zone_of_[v])
      if (occupied[z] && std::find(zone_of_[u].begin(), zone_of_[u].end(), z) == zone_of_[u].end()) return true;
    return false;
  });
}

planner::Config Rules::goals(const planner::Graph& g, const planner::Config& at, const planner::Config& goals,
                             std::vector<uint8_t>& waiting, double t, std::vector<std::string>& lines)
{
  const size_t n = at.size();
  waiting.assign(n, 0);
  if (waiting_.size() != n) waiting_.assign(n, 0);
  int count = 0;
  const std::vector<int> comp = g.strong_components(&count);
  planner::Config eff = goals;
  std::unordered_set<planner::Vertex> taken(goals.begin(), goals.end());
  for (size_t i = 0; i < n; ++i) {
    const bool reach = comp[at[i]] == comp[goals[i]] || g.reaches(at[i], goals[i]);
    if (reach) continue;
    waiting[i] = 1;
    // Wait on the nearest reachable cell that is open, in no zone and nobody's goal.
    planner::Vertex best = at[i];
    std::vector<uint8_t> seen(g.size(), 0);
    std::vector<planner::Vertex> queue{at[i]};
    seen[at[i]] = 1;
    for (size_t h = 0; h < queue.size(); ++h) {
      const planner::Vertex v = queue[h];
      if (!closed_[v] && zone_of_[v].empty() && (!taken.count(v) || v == goals[i])) {
        best = v;
        break;
      }
      for (planner::Vertex w : g.neighbors(v))
        if (!seen[w]) seen[w] = 1, queue.push_back(w);
    }
    eff[i] = best;
    taken.insert(best);
  }
  // Lines: an AGV starts or stops waiting because of a closure.
  for (size_t i = 0; i < n; ++i) {
    const bool for_closure = waiting[i] && (num_closed_ > 0 || !closed_arcs_.empty());
    if (for_closure == static_cast<bool>(waiting_[i])) continue;
    waiting_[i] = for_closure;
    char when[48];
    std::snprintf(when, sizeof when, "t=%.1f s: ", t);
    const std::string id = Commander::vehicle_id(static_cast<int>(i));
    if (!for_closure)
      lines.push_back(when + id + " goes on to its goal (cell " + std::to_string(goals[i]) + ")");
    else if (closed_[goals[i]])
      lines.push_back(when + id + " waits: its goal (cell " + std::to_string(goals[i]) + ") is closed by " +
                      closed_by(goals[i]));
    else
      lines.push_back(when + id + " waits: its goal (cell " + std::to_string(goals[i]) + ") is cut off by closed cells");
  }
  return eff;
}

int Rules::count_held(const std::vector<int>& gated, const planner::Config& at)
{
  if (zone_held_.size() != zones_.size()) zone_held_.assign(zones_.size(), 0);
  const std::vector<uint8_t> occ = occupied(at);
  std::vector<uint8_t> held(zones_.size(), 0);
  int n = 0;
  for (int z : gated)
    if (z >= 0) held[z] = 1, ++n;
  for (size_t z = 0; z < zones_.size(); ++z)
    if (held[z]) ++zone_held_[z];
    else if (!occ[z]) zone_held_[z] = 0;  // empty again: the count starts over with the next occupant
  return n;
}

int Rules::admit(const planner::Config& cur, planner::Config& next)
{
  const size_t n = cur.size();
  if (zone_wait_.size() != n) zone_wait_.assign(n, 0);
  if (zone_held_.size() != zones_.size()) zone_held_.assign(zones_.size(), 0);
  planner::Config out = next;
  int held = 0;
  // Hold agent i (stay on cur[i]), and whoever moves into its cell, transitively.
  std::function<void(size_t)> hold = [&](size_t i) {
    if (out[i] == cur[i]) return;
    out[i] = cur[i];
    ++held;
    for (size_t j = 0; j < n; ++j)
      if (j != i && out[j] == cur[i]) hold(j);
  };
  for (size_t z = 0; z < zones_.size(); ++z) {
    auto in = [&](planner::Vertex v) { return std::find(zone_of_[v].begin(), zone_of_[v].end(), static_cast<int>(z)) != zone_of_[v].end(); };
    bool inside = false;
    std::vector<size_t> entrants;
    for (size_t i = 0; i < n; ++i) {
      if (in(cur[i])) inside = true;
      else if (in(out[i])) entrants.push_back(i);
    }
    if (entrants.empty() || (!inside && entrants.size() == 1)) {
      if (!inside) zone_held_[z] = 0;  // empty again: the count starts over with the next occupant
      continue;
    }
    ++zone_held_[z];
    // Keep the one inside; else the entrant that waited longest (then the lowest index).
    size_t keep = n;
    if (!inside)
      for (size_t i : entrants)
        if (keep == n || zone_wait_[i] > zone_wait_[keep]) keep = i;
    for (size_t i : entrants)
      if (i != keep) hold(i);
  }
  for (size_t i = 0; i < n; ++i) {
    bool enters = false;
    for (int z : zone_of_[next[i]]) enters = enters || std::find(zone_of_[cur[i]].begin(), zone_of_[cur[i]].end(), z) == zone_of_[cur[i]].end();
    zone_wait_[i] = enters && out[i] == cur[i] ? zone_wait_[i] + 1 : 0;
  }
  next = out;
  return held;
}

}  // namespace controller
