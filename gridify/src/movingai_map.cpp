#include "gridify/movingai_map.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "planner/error.hpp"
#include "planner/output_file.hpp"

namespace gridify {

GridLayout grid_layout(const CellMap& m, std::string* why)
{
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return GridLayout{};
  };
  const double c = m.cell_length, tol = 1e-3 * c;
  if (m.cells.empty()) return fail("no cells");
  for (const Aisle& a : m.aisles) {
    if (a.snapped) return fail("aisle '" + a.ab + "' was snapped to spacing " + std::to_string(a.spacing));
    // Ends whose junction was dropped are -1 in Aisle::cells: compare the kept extremes.
    auto first = std::find_if(a.cells.begin(), a.cells.end(), [](planner::Vertex v) { return v >= 0; });
    auto last = std::find_if(a.cells.rbegin(), a.cells.rend(), [](planner::Vertex v) { return v >= 0; });
    if (first == a.cells.end() || *first == *last) continue;
    const Cell &ca = m.cells[*first], &cb = m.cells[*last];
    if (std::fabs(ca.x - cb.x) > tol && std::fabs(ca.y - cb.y) > tol)
      return fail("aisle '" + a.ab + "' is not axis-aligned");
  }
  double minx = std::numeric_limits<double>::infinity(), maxy = -minx;
  for (const Cell& cell : m.cells) minx = std::min(minx, cell.x), maxy = std::max(maxy, cell.y);
  GridLayout L;
  for (const Cell& cell : m.cells) {
    double fx = (cell.x - minx) / c, fy = (maxy - cell.y) / c;
    // Bound before converting to int: a cell 2^31 cell lengths away overflowed col + 1.
    if (fx > 1e8 || fy > 1e8) return fail("the lattice is too large");
    GridCoord g{static_cast<int>(std::lround(fx)), static_cast<int>(std::lround(fy))};
    if (std::fabs(fx - g.col) * c > tol || std::fabs(fy - g.row) * c > tol)
      return fail("a cell at (" + std::to_string(cell.x) + ", " + std::to_string(cell.y) + ") is off the lattice");
    L.width = std::max(L.width, g.col + 1);
    L.height = std::max(L.height, g.row + 1);
    L.coord.push_back(g);
  }
  if (static_cast<double>(L.width) * L.height > 1e8) return fail("the lattice is too large");
  std::vector<planner::Vertex> at(static_cast<size_t>(L.width) * L.height, -1);
  for (planner::Vertex v = 0; v < static_cast<planner::Vertex>(L.coord.size()); ++v) {
    planner::Vertex& slot = at[static_cast<size_t>(L.coord[v].row) * L.width + L.coord[v].col];
    if (slot >= 0) return fail("two cells share a lattice point");
    slot = v;
  }
  // The 4-neighbour graph of the lattice must equal the gridified graph.
  for (planner::Vertex v = 0; v < static_cast<planner::Vertex>(L.coord.size()); ++v) {
    for (planner::Vertex u : m.graph.neighbors(v))
      if (std::abs(L.coord[u].col - L.coord[v].col) + std::abs(L.coord[u].row - L.coord[v].row) != 1)
        return fail("a graph edge joins cells that are not lattice neighbours");
    const int dc[] = {1, 0}, dr[] = {0, 1};
    for (int d = 0; d < 2; ++d) {
      int col = L.coord[v].col + dc[d], row = L.coord[v].row + dr[d];
      if (col >= L.width || row >= L.height) continue;
      planner::Vertex u = at[static_cast<size_t>(row) * L.width + col];
      if (u >= 0 && !m.graph.adjacent(u, v) && !m.graph.adjacent(v, u))  // a one-way arc is a link too
        return fail("neighbouring cells " + std::to_string(v) + " and " + std::to_string(u) +
                    " are not connected in SUMO (aisles one cell apart?)");
    }
  }
  return L;
}

void write_movingai_map(const CellMap& m, const std::string& path)
{
  std::string why;
  GridLayout L = grid_layout(m, &why);
  if (L.width == 0) throw planner::InputError(m.net_path + ": cannot write a MovingAI map: " + why);
  // A .map has two-way moves only: it would turn every one-way aisle into a two-way one.
  if (m.graph.directed())
    throw planner::InputError(m.net_path + ": cannot write a MovingAI map: " + std::to_string(m.graph.num_one_way()) +
                              " one-way arc(s) (a .map has only two-way moves)");
  std::vector<std::string> rows(L.height, std::string(L.width, '@'));
  for (const GridCoord& g : L.coord) rows[g.row][g.col] = '.';
  planner::write_file(path, [&](std::ostream& out) {
    out << "type octile\nheight " << L.height << "\nwidth " << L.width << "\nmap\n";
    for (const std::string& r : rows) out << r << '\n';
  });
}

}  // namespace gridify
