#include "planner/rotation/guidance.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "planner/error.hpp"
#include "planner/heading.hpp"
#include "planner/output_file.hpp"

namespace planner {

namespace {
Vertex ahead(const Graph& g, Vertex v, int o) { return cell_ahead(g, v, o); }

// Strongly connected components of the cells over the arcs of cost <= cheap (Kosaraju,
// iterative: maps have 10^5 cells, too deep for recursion).
std::vector<int32_t> cheap_components(const Graph& g, const Guidance& gd, uint16_t cheap)
{
  const Vertex n = g.size();
  auto arc = [&](Vertex v, int o, bool reverse) -> Vertex {
    // reverse: the arc into v from the cell behind it, facing o
    const Vertex u = reverse ? cell_behind(g, v, o) : ahead(g, v, o);
    if (u < 0) return -1;
    return gd.forward_cost(reverse ? u : v, o) <= cheap ? u : -1;
  };
  std::vector<Vertex> order;
  order.reserve(static_cast<size_t>(n));
  std::vector<char> seen(static_cast<size_t>(n), 0);
  std::vector<std::pair<Vertex, int>> st;
  for (Vertex r = 0; r < n; ++r) {
    if (seen[r]) continue;
    seen[r] = 1;
    st.push_back({r, 0});
    while (!st.empty()) {
      auto& [v, o] = st.back();
      if (o == 4) {
        order.push_back(v);
        st.pop_back();
        continue;
      }
      const Vertex u = arc(v, o++, false);
      if (u >= 0 && !seen[u]) seen[u] = 1, st.push_back({u, 0});
    }
  }
  std::vector<int32_t> comp(static_cast<size_t>(n), -1);
  int32_t c = 0;
  std::vector<Vertex> stack;
  for (auto it = order.rbegin(); it != order.rend(); ++it, ++c) {
    if (comp[*it] >= 0) {
      --c;
      continue;
    }
    comp[*it] = c;
    stack.push_back(*it);
    while (!stack.empty()) {
      const Vertex v = stack.back();
      stack.pop_back();
      for (int o = 0; o < 4; ++o) {
        const Vertex u = arc(v, o, true);
        if (u >= 0 && comp[u] < 0) comp[u] = c, stack.push_back(u);
      }
    }
  }
  return comp;
}

// Per row (rows: true) or column: whether it is an "even" lane of the field. The lanes are
// the rows (columns) that hold a move along them, numbered in order, and they alternate by
// that number, so aisles any distance apart alternate: by coordinate parity, a warehouse
// with an aisle every 4th column would get all of them one way, and the repair would then
// make every arc cheap (no guidance left). The count starts at the first lane's own parity,
// so a map whose every row and column is a lane (LoRR's and most MovingAI maps) gets the
// parity field unchanged.
std::vector<char> lane_parity(const Graph& g, bool rows)
{
  const int n = rows ? g.height() : g.width();
  std::vector<char> lane(static_cast<size_t>(n), 0), even(static_cast<size_t>(n), 0);
  const int o = rows ? 0 : 1;  // east: along a row; south: along a column
  for (Vertex v = 0; v < g.size(); ++v)
    if (ahead(g, v, o) >= 0 || ahead(g, v, reversed(o)) >= 0) lane[static_cast<size_t>(rows ? g.cell_y(v) : g.cell_x(v))] = 1;
  int k = -1;
  for (int i = 0; i < n; ++i) {
    if (!lane[static_cast<size_t>(i)]) {
      even[static_cast<size_t>(i)] = i % 2 == 0;  // no move along it: its field is never read
      continue;
    }
    k = k < 0 ? i % 2 : k + 1;
    even[static_cast<size_t>(i)] = k % 2 == 0;
  }
  return even;
}

void check_cost(long c, const std::string& what)
{
  if (c < 1 || c > Guidance::kMaxCost)
    throw std::invalid_argument(what + " must be in 1.." + std::to_string(Guidance::kMaxCost) + ", got " + std::to_string(c));
}
}  // namespace

bool Guidance::uniform() const
{
  return turn == 1 && std::all_of(forward.begin(), forward.end(), [](uint16_t c) { return c == 1; });
}

uint16_t Guidance::min_forward() const
{
  return forward.empty() ? 1 : *std::min_element(forward.begin(), forward.end());
}

uint16_t Guidance::max_cost() const
{
  return std::max<uint16_t>(turn, forward.empty() ? 1 : *std::max_element(forward.begin(), forward.end()));
}

Guidance arrow_guidance(const Graph& g, int along, int against, int turn)
{
  if (!g.is_grid()) throw std::invalid_argument("arrow guidance needs a grid graph");
  check_cost(along, "arrow cost along");
  check_cost(against, "arrow cost against");
  check_cost(turn, "arrow turn cost");
  Guidance gd;
  gd.turn = static_cast<uint16_t>(turn);
  gd.forward.assign(static_cast<size_t>(g.size()) * 4, static_cast<uint16_t>(along));
  const std::vector<char> east = lane_parity(g, true), south = lane_parity(g, false);
  for (Vertex v = 0; v < g.size(); ++v)
    for (int o = 0; o < 4; ++o) {
      // Rows: "even" lanes east (o 0), odd ones west; columns: even south (o 1), odd north.
      const bool with = o % 2 == 0 ? (o == 0) == static_cast<bool>(east[static_cast<size_t>(g.cell_y(v))])
                                   : (o == 1) == static_cast<bool>(south[static_cast<size_t>(g.cell_x(v))]);
      if (!with) gd.forward[static_cast<size_t>(v) * 4 + o] = static_cast<uint16_t>(against);
    }
  if (against <= along) return gd;
  // Repair: costly arcs between the cheap arcs' components become cheap until none is left.
  for (bool changed = true; changed;) {
    changed = false;
    const std::vector<int32_t> comp = cheap_components(g, gd, static_cast<uint16_t>(along));
    for (Vertex v = 0; v < g.size(); ++v)
      for (int o = 0; o < 4; ++o) {
        const Vertex u = ahead(g, v, o);
        uint16_t& c = gd.forward[static_cast<size_t>(v) * 4 + o];
        if (u >= 0 && c > along && comp[u] != comp[v]) c = static_cast<uint16_t>(along), changed = true;
      }
  }
  return gd;
}

bool cheap_arcs_strongly_connected(const Graph& g, const Guidance& gd, uint16_t cheap)
{
  const std::vector<int32_t> comp = cheap_components(g, gd, cheap);
  for (Vertex v = 0; v < g.size(); ++v)
    for (Vertex u : g.neighbors(v))
      if (comp[u] != comp[v]) return false;  // joined by the map, not by cheap arcs
  return true;
}

Guidance load_guidance(const Graph& g, const std::string& path)
{
  if (!g.is_grid()) throw input_error(path, 0, "guidance needs a grid map");
  check_not_directory(path);  // else read as an empty guidance file
  std::ifstream in(path);
  if (!in) throw input_error(path, 0, "cannot open guidance file");
  Guidance gd;
  long dflt = 1;
  std::vector<long> cell(static_cast<size_t>(g.size()) * 4, 0);  // 0: not listed
  std::vector<char> listed(static_cast<size_t>(g.size()), 0);
  std::string line;
  int no = 0;
  auto cost = [&](const std::string& tok, const std::string& what) {
    size_t end = 0;
    long c = 0;
    try {
      c = std::stol(tok, &end);
    } catch (const std::exception&) {
      end = 0;
    }
    if (end != tok.size() || end == 0) throw input_error(path, no, what + ": '" + tok + "' is not an integer");
    if (c < 1 || c > Guidance::kMaxCost)
      throw input_error(path, no, what + " " + tok + " out of range 1.." + std::to_string(Guidance::kMaxCost));
    return c;
  };
  while (std::getline(in, line)) {
    ++no;
    if (const size_t h = line.find('#'); h != std::string::npos) line.resize(h);
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string t; ls >> t;) tok.push_back(t);
    if (tok.empty()) continue;
    if (tok[0] == "turn" || tok[0] == "default") {
      if (tok.size() != 2) throw input_error(path, no, "expected '" + tok[0] + " COST'");
      const long c = cost(tok[1], tok[0] + " cost");
      if (tok[0] == "turn") gd.turn = static_cast<uint16_t>(c);
      else dflt = c;
      continue;
    }
    if (tok.size() != 6) throw input_error(path, no, "expected 'X Y COST_E COST_S COST_W COST_N', 'turn COST' or 'default COST'");
    int xy[2];
    for (int k = 0; k < 2; ++k) {
      size_t end = 0;
      try {
        xy[k] = std::stoi(tok[static_cast<size_t>(k)], &end);
      } catch (const std::exception&) {
        end = 0;
      }
      if (end == 0 || end != tok[static_cast<size_t>(k)].size())
        throw input_error(path, no, std::string(k ? "Y" : "X") + " '" + tok[static_cast<size_t>(k)] + "' is not an integer");
    }
    const Vertex v = g.at(xy[0], xy[1]);
    if (v < 0) throw input_error(path, no, "cell (" + tok[0] + ", " + tok[1] + ") is off the map or an obstacle");
    if (listed[v]) throw input_error(path, no, "cell (" + tok[0] + ", " + tok[1] + ") listed twice");
    listed[v] = 1;
    static const char* dirs[4] = {"east", "south", "west", "north"};
    for (int o = 0; o < 4; ++o) cell[static_cast<size_t>(v) * 4 + o] = cost(tok[static_cast<size_t>(2 + o)], std::string("cost ") + dirs[o]);
  }
  gd.forward.assign(cell.size(), 1);
  for (size_t k = 0; k < cell.size(); ++k) gd.forward[k] = static_cast<uint16_t>(cell[k] ? cell[k] : dflt);
  return gd;
}

void save_guidance(const Graph& g, const Guidance& gd, const std::string& path, const std::string& header)
{
  write_file(path, [&](std::ostream& out) {
    std::istringstream hs(header);
    for (std::string l; std::getline(hs, l);) out << "# " << l << '\n';
    out << "# rotation guidance: X Y forward cost facing east south west north\nturn " << gd.turn << "\n";
    for (Vertex v = 0; v < g.size(); ++v) {
      out << g.cell_x(v) << ' ' << g.cell_y(v);
      for (int o = 0; o < 4; ++o) out << ' ' << gd.forward_cost(v, o);
      out << '\n';
    }
  });
}

}  // namespace planner
