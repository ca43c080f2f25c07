#include "gridify/gridifier.hpp"

#include "gridify/movingai_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "planner/error.hpp"

namespace gridify {

namespace {

std::string num(double d)
{
  std::ostringstream s;
  s << d;
  return s.str();
}

// Step 3: number of cell steps along each aisle.
void cut_aisles(const NetFile& net, std::vector<Aisle>& aisles, const GridifyOptions& opt, std::vector<std::string>& warnings)
{
  int snapped = 0, off_distance = 0, multi_lane = 0;
  std::string off_example, multi_example;
  long long cells = static_cast<long long>(net.junctions.size());
  for (Aisle& a : aisles) {
    const NetEdge& e = *net.edge(a.ab);
    // AGVs drive lane 0 only (one AGV per cell); wider edges are accepted but said so.
    for (const NetEdge* d : {&e, a.one_way ? &e : net.edge(a.ba)})
      if (d->lanes.size() > 1 && multi_lane++ == 0) multi_example = d->id + " (" + std::to_string(d->lanes.size()) + " lanes)";
    if (!a.one_way && std::fabs(a.length_ab - a.length_ba) > opt.tolerance)
      throw planner::input_error(net.path, e.line,
                                 "edges '" + a.ab + "' and '" + a.ba + "' of one aisle differ in length (" + num(a.length_ab) +
                                     " vs " + num(a.length_ba) + ")");
    // Bound the step count before rounding it: a 3e9 m lane overflowed `int` steps (out of
    // bounds writes), a 1e9 m one allocated a billion cells.
    const double q = a.length_ab / opt.cell_length;
    if (q > kMaxCells)
      throw planner::input_error(net.path, e.line,
                                 "edge '" + a.ab + "': length " + num(a.length_ab) + " is more than " +
                                     std::to_string(kMaxCells) + " cells of cell_length " + num(opt.cell_length));
    long n = std::lround(q);
    bool fits = n >= 1 && std::fabs(a.length_ab - n * opt.cell_length) <= opt.tolerance;
    if (fits) {
      // Cells split the lane exactly: an 8.99 m aisle of 1 m cells (netconvert's rounding on
      // random or diagonal nets) has steps of 0.99889 m, so its last cell is the junction.
      // With steps of cell_length the junction sat 10 mm past the last step, where Safety
      // saw an AGV at the junction as between two cells (exit 3).
      a.steps = static_cast<int>(n);
      a.spacing = a.length_ab / a.steps;
    } else if (opt.snap) {
      a.steps = static_cast<int>(std::max(1L, n));
      a.spacing = a.length_ab / a.steps;
      a.snapped = true;
      ++snapped;
    } else {
      std::string what = a.length_ab < opt.cell_length ? "is shorter than" : "is not a multiple of";
      throw planner::input_error(net.path, e.line,
                                 "edge '" + a.ab + "': length " + num(a.length_ab) + " " + what + " cell_length " +
                                     num(opt.cell_length) + " (use --snap)");
    }
    if ((cells += a.steps - 1) > kMaxCells)
      throw planner::input_error(net.path, e.line,
                                 "the net has more than " + std::to_string(kMaxCells) + " cells of cell_length " +
                                     num(opt.cell_length) + " (reached at edge '" + a.ab + "')");
    // The model assumes lane length == distance between the junction centres.
    const NetJunction &ja = *net.junction(a.a), &jb = *net.junction(a.b);
    double dist = std::hypot(jb.x - ja.x, jb.y - ja.y);
    if (std::fabs(dist - a.length_ab) > std::max(opt.tolerance, 1e-3 * dist)) {
      if (off_distance++ == 0) off_example = a.ab + " (length " + num(a.length_ab) + ", junctions " + num(dist) + " apart)";
    }
  }
  if (snapped)
    warnings.push_back("snapped " + std::to_string(snapped) + " aisle(s) whose length is not a multiple of cell_length " +
                       num(opt.cell_length));
  if (multi_lane)
    warnings.push_back(std::to_string(multi_lane) + " edge(s) with more than one lane, e.g. " + multi_example +
                       "; AGVs use lane 0 and connections between lanes 0 only");
  if (off_distance)
    warnings.push_back(std::to_string(off_distance) + " aisle(s) whose lane length differs from the junction distance, e.g. " +
                       off_example + "; cells are displayed between junction centres");
}

// Which junction<->aisle links exist (step 4). link[i][0] is aisle i's link at A, [1] at B.
// A link at J needs a connection into the aisle's edge leaving J and a connection out of
// the aisle's edge arriving at J, both from/to edges whose own links at J exist: iterate
// to the fixpoint because dropping one link can strand a connection of another. A one-way
// aisle has one edge: at A it needs only the connection into it, at B only the one out.
std::vector<std::array<bool, 2>> find_links(const NetFile& net, const std::vector<Aisle>& aisles)
{
  // edge id -> (aisle, end at its *to* junction: 0 = A, 1 = B)
  std::unordered_map<std::string, std::pair<int, int>> arrives, leaves;
  for (int i = 0; i < static_cast<int>(aisles.size()); ++i) {
    arrives[aisles[i].ab] = {i, 1};
    leaves[aisles[i].ab] = {i, 0};
    if (aisles[i].one_way) continue;
    arrives[aisles[i].ba] = {i, 0};
    leaves[aisles[i].ba] = {i, 1};
  }
  std::vector<std::array<bool, 2>> link(aisles.size(), {true, true});
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::array<bool, 2>> can_enter(aisles.size(), {false, false}), can_leave = can_enter;
    for (const NetConnection& c : net.connections) {
      if (c.from_lane != 0 || c.to_lane != 0) continue;
      auto in = arrives.find(c.from);
      auto out = leaves.find(c.to);
      if (in == arrives.end() || out == leaves.end()) continue;
      auto [ia, iend] = in->second;
      auto [oa, oend] = out->second;
      if (!link[ia][iend] || !link[oa][oend]) continue;
      can_leave[ia][iend] = true;
      can_enter[oa][oend] = true;
    }
    for (size_t i = 0; i < aisles.size(); ++i)
      for (int end = 0; end < 2; ++end) {
        const bool need_enter = end == 0 || !aisles[i].one_way, need_leave = end == 1 || !aisles[i].one_way;
        if (link[i][end] && !((can_enter[i][end] || !need_enter) && (can_leave[i][end] || !need_leave)))
          link[i][end] = false, changed = true;
      }
  }
  return link;
}

std::string list_ids(const std::vector<std::string>& ids, size_t max_shown = 6)
{
  std::string s;
  for (size_t k = 0; k < ids.size() && k < max_shown; ++k) s += (k ? ", " : "") + ids[k];
  if (ids.size() > max_shown) s += ", ... (" + std::to_string(ids.size()) + " in all)";
  return s;
}

}  // namespace

CellMap gridify(const std::string& net_path, const GridifyOptions& opt)
{
  return gridify(NetFile::read(net_path), opt);
}

CellMap gridify(const NetFile& net, const GridifyOptions& opt)
{
  if (!(opt.cell_length > 0) || !std::isfinite(opt.cell_length))
    throw planner::InputError("cell_length must be a positive number, got " + num(opt.cell_length));
  // Step 1.
  if (!net.internal_example.empty())
    throw planner::input_error(net.path, 0,
                               "the net has internal links (e.g. '" + net.internal_example +
                                   "'); rebuild it with netconvert --no-internal-links (see gridify/README.md)");

  CellMap m;
  m.net_path = net.path;
  m.cell_length = opt.cell_length;

  // Step 2 and 3.
  std::vector<Aisle> aisles = pair_aisles(net, opt.drop_one_way, m.dropped);
  if (aisles.empty()) {
    for (const Dropped& d : m.dropped)
      if (d.kind == "closed edge")
        throw planner::input_error(net.path, 0, "no aisles the AGVs may drive: edge '" + d.id + "': " + d.reason);
    throw planner::input_error(net.path, 0, "no aisles (pairs of opposite edges) in the net");
  }
  cut_aisles(net, aisles, opt, m.warnings);

  // Step 4: provisional cells (junctions first, in file order), then aisle interiors.
  std::vector<Cell> cells;
  std::unordered_map<std::string, planner::Vertex> jcell;
  for (const NetJunction& j : net.junctions) {
    Cell c;
    c.kind = CellKind::Junction;
    c.x = j.x;
    c.y = j.y;
    c.junction = j.id;
    jcell[j.id] = static_cast<planner::Vertex>(cells.size());
    cells.push_back(std::move(c));
  }
  auto links = find_links(net, aisles);
  std::vector<std::pair<planner::Vertex, planner::Vertex>> arcs;  // moves: both ways on two-way aisles
  std::vector<std::string> unlinked;
  for (int i = 0; i < static_cast<int>(aisles.size()); ++i) {
    Aisle& a = aisles[i];
    const NetJunction &ja = *net.junction(a.a), &jb = *net.junction(a.b);
    a.cells.push_back(jcell[a.a]);
    for (int k = 1; k < a.steps; ++k) {
      Cell c;
      c.kind = CellKind::Aisle;
      c.aisle = i;
      c.k = k;
      double f = static_cast<double>(k) / a.steps;
      c.x = ja.x + (jb.x - ja.x) * f;
      c.y = ja.y + (jb.y - ja.y) * f;
      c.poses = {{a.lane_ab, k * a.spacing}};
      if (!a.one_way) c.poses.push_back({a.lane_ba, std::max(0.0, a.length_ba - k * a.spacing)});
      a.cells.push_back(static_cast<planner::Vertex>(cells.size()));
      cells.push_back(std::move(c));
    }
    a.cells.push_back(jcell[a.b]);
    for (int k = 0; k < a.steps; ++k) {
      bool at_a = k == 0, at_b = k + 1 == a.steps;
      if ((at_a && !links[i][0]) || (at_b && !links[i][1])) continue;
      arcs.emplace_back(a.cells[k], a.cells[k + 1]);
      if (!a.one_way) arcs.emplace_back(a.cells[k + 1], a.cells[k]);
    }
    for (int end = 0; end < 2; ++end) {
      if (links[i][end]) continue;
      const std::string& j = end ? a.b : a.a;
      std::string id = j + "/" + (end && !a.one_way ? a.ba : a.ab);
      unlinked.push_back(id);
      // Draw just the missing link: junction centre to the neighbouring cell.
      const NetJunction &from = end ? jb : ja, &to = end ? ja : jb;
      planner::Point p{from.x, from.y}, q{from.x + (to.x - from.x) / a.steps, from.y + (to.y - from.y) / a.steps};
      const std::string why = !a.one_way ? "enter '" + (end ? a.ba : a.ab) + "' or leave '" + (end ? a.ab : a.ba) + "'"
                              : end    ? "leave '" + a.ab + "'"
                                       : "enter '" + a.ab + "'";
      m.dropped.push_back({"link", id, "no SUMO connection lets a vehicle at junction '" + j + "' " + why + " there",
                           {{p, q}},
                           {}});
    }
  }

  // Step 5: keep the largest strongly connected component: every kept cell can reach every
  // other and come back (lifelong errands go anywhere). With two-way aisles only, these are
  // the connected components.
  const int n0 = static_cast<int>(cells.size());
  planner::Graph g0 = planner::Graph::from_arcs(n0, arcs);
  int ncomp = 0;
  std::vector<int> comp = g0.strong_components(&ncomp);
  std::vector<int> comp_size(ncomp, 0);
  for (int c : comp) ++comp_size[c];
  int keep = static_cast<int>(std::max_element(comp_size.begin(), comp_size.end()) - comp_size.begin());
  if (ncomp > 1) {
    std::vector<std::vector<std::string>> comp_junctions(ncomp);
    for (int v = 0; v < n0; ++v)
      if (cells[v].kind == CellKind::Junction) comp_junctions[comp[v]].push_back(cells[v].junction);
    auto name = [&](int c) {
      return comp_junctions[c].empty() ? std::string("(aisle cells only)") : list_ids(comp_junctions[c]);
    };
    if (!opt.keep_largest) {
      int other = keep == 0 ? 1 : 0;
      throw planner::input_error(net.path, 0,
                                 std::string(g0.directed() ? "the net is not strongly connected (" : "the net is disconnected (") +
                                     std::to_string(ncomp) + " components): junctions " + name(other) +
                                     (g0.directed() ? " cannot reach and be reached from junctions " : " are cut off from junctions ") +
                                     name(keep));
    }
    std::vector<Dropped> parts(ncomp);
    for (const Aisle& a : aisles) {
      int c = comp[a.cells[1]];
      if (c != keep) {
        const NetJunction &ja = *net.junction(a.a), &jb = *net.junction(a.b);
        parts[c].segments.push_back({{ja.x, ja.y}, {jb.x, jb.y}});
        parts[c].members.push_back(a.ab);
        if (!a.one_way) parts[c].members.push_back(a.ba);
      }
    }
    for (int v = 0; v < n0; ++v)  // dropped junctions as points (zero-length segments)
      if (comp[v] != keep && cells[v].kind == CellKind::Junction)
        parts[comp[v]].segments.push_back({{cells[v].x, cells[v].y}, {cells[v].x, cells[v].y}});
    for (int c = 0; c < ncomp; ++c) {
      if (c == keep) continue;
      parts[c].kind = "component";
      parts[c].id = name(c);
      parts[c].members.insert(parts[c].members.end(), comp_junctions[c].begin(), comp_junctions[c].end());
      parts[c].reason = std::to_string(comp_size[c]) + " cell(s) not connected to the largest component (" +
                        std::to_string(comp_size[keep]) + " cells)";
      m.dropped.push_back(std::move(parts[c]));
    }
  }

  std::vector<planner::Vertex> id(n0, -1);
  for (int v = 0; v < n0; ++v)
    if (comp[v] == keep) {
      id[v] = static_cast<planner::Vertex>(m.cells.size());
      m.cells.push_back(std::move(cells[v]));
    }
  std::vector<std::pair<planner::Vertex, planner::Vertex>> kept_arcs;
  for (auto [u, v] : arcs)
    if (id[u] >= 0 && id[v] >= 0) kept_arcs.emplace_back(id[u], id[v]);

  // Kept aisles: those whose interior cells were kept, or (no interior cell) whose single
  // graph edge was kept. Dropped chain ends become -1 in Aisle::cells.
  std::vector<int> aisle_index(aisles.size(), -1);
  for (size_t i = 0; i < aisles.size(); ++i) {
    Aisle& a = aisles[i];
    bool kept = a.steps > 1 ? comp[a.cells[1]] == keep
                            : links[i][0] && links[i][1] && comp[a.cells[0]] == keep && comp[a.cells[1]] == keep;
    for (planner::Vertex& v : a.cells) v = id[v];
    if (!kept) continue;
    int idx = aisle_index[i] = static_cast<int>(m.aisles.size());
    for (size_t k = 1; k + 1 < a.cells.size(); ++k) m.cells[a.cells[k]].aisle = idx;
    m.lane_aisle[a.lane_ab] = {idx, true};
    if (!a.one_way) m.lane_aisle[a.lane_ba] = {idx, false};
    m.aisles.push_back(a);
  }

  // Junction poses (one per incoming linked edge) and movements between linked edges.
  for (planner::Vertex v = 0; v < static_cast<planner::Vertex>(m.cells.size()); ++v)
    if (m.cells[v].kind == CellKind::Junction) m.junction_cells[m.cells[v].junction] = v;
  // Edges a vehicle may arrive on at a junction cell / leave a junction cell by.
  std::unordered_set<std::string> linked_in, linked_out;
  for (size_t i = 0; i < aisles.size(); ++i) {
    if (aisle_index[i] < 0) continue;
    const Aisle& a = aisles[i];
    if (links[i][1]) linked_in.insert(a.ab);
    if (links[i][0]) linked_out.insert(a.ab);
    if (links[i][1]) m.cells[a.cells.back()].poses.push_back({a.lane_ab, a.length_ab});
    if (a.one_way) continue;
    if (links[i][1]) linked_out.insert(a.ba);
    if (links[i][0]) linked_in.insert(a.ba);
    if (links[i][0]) m.cells[a.cells.front()].poses.push_back({a.lane_ba, a.length_ba});
  }
  int missing = 0;
  std::string missing_example;
  std::set<std::pair<std::string, std::string>> have;
  for (const NetConnection& c : net.connections) {
    if (c.from_lane != 0 || c.to_lane != 0 || !linked_in.count(c.from) || !linked_out.count(c.to)) continue;
    planner::Vertex j = m.junction_cell(net.edge(c.from)->to);
    if (j < 0) continue;
    m.cells[j].movements.push_back({c.from, c.to, c.dir});
    have.insert({c.from, c.to});
  }
  // Count turns a vehicle parked on a junction cell may be asked for but SUMO lacks.
  std::unordered_map<std::string, std::vector<const NetEdge*>> out_at;
  for (const NetEdge& o : net.edges)
    if (linked_out.count(o.id)) out_at[o.from].push_back(&o);
  for (const NetEdge& e : net.edges) {
    if (!linked_in.count(e.id)) continue;
    for (const NetEdge* o : out_at[e.to]) {
      if (have.count({e.id, o->id})) continue;
      if (missing++ == 0) missing_example = "'" + e.id + "' -> '" + o->id + "' at '" + e.to + "'";
    }
  }
  if (missing)
    m.warnings.push_back(std::to_string(missing) + " turn(s) between kept edges have no SUMO connection, e.g. " +
                         missing_example + "; the controller must reposition (moveTo) for them");
  if (!unlinked.empty())
    m.warnings.push_back(std::to_string(unlinked.size()) + " junction-aisle link(s) dropped for lack of SUMO connections: " +
                         list_ids(unlinked));

  std::vector<planner::Point> pos;
  pos.reserve(m.cells.size());
  for (const Cell& c : m.cells) pos.push_back({c.x, c.y});
  m.graph = planner::Graph::from_arcs(static_cast<int>(m.cells.size()), kept_arcs, std::move(pos));
  m.graph.name = net.path;
  // An axis-aligned lattice net also gets the planner's grid view (MovingAI-style cells),
  // which grid-based tools such as the learned policy's observations need.
  if (const GridLayout L = grid_layout(m); L.width > 0) {
    std::vector<int32_t> cells;
    cells.reserve(L.coord.size());
    for (const GridCoord& c : L.coord) cells.push_back(c.row * L.width + c.col);
    m.graph.attach_grid(L.width, L.height, std::move(cells));
  }

  // Step 6.
  if (!opt.additional.empty()) tag_stations(m, net, opt.additional);
  return m;
}

}  // namespace gridify
