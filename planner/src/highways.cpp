#include "planner/highways.hpp"

#include <algorithm>

namespace planner {

namespace {

// The grain of every cell's horizontal (axis 0) or vertical (axis 1) run: +1 / -1 along the
// axis, 0 where the cell is in no qualifying run.
std::vector<int8_t> grains(const Graph& g, int axis, int min_run)
{
  const int W = g.width(), H = g.height();
  auto free = [&](int x, int y) { return g.at(x, y) >= 0; };
  // Cell (a, b): a along the run, b across it.
  auto cell = [&](int a, int b) { return axis == 0 ? g.at(a, b) : g.at(b, a); };
  auto narrow = [&](int a, int b) {
    return axis == 0 ? free(a, b) && !free(a, b - 1) && !free(a, b + 1) : free(b, a) && !free(b - 1, a) && !free(b + 1, a);
  };
  const int along = axis == 0 ? W : H, across = axis == 0 ? H : W;
  std::vector<int8_t> out(static_cast<size_t>(g.size()), 0);
  int line = 0;  // lines (rows / columns) with a run, numbered in order
  for (int b = 0; b < across; ++b) {
    bool any = false;
    for (int a = 0; a < along;) {
      if (!narrow(a, b)) {
        ++a;
        continue;
      }
      int e = a;
      while (e < along && narrow(e, b)) ++e;
      if (e - a >= min_run) {
        any = true;
        for (int k = a; k < e; ++k) out[static_cast<size_t>(cell(k, b))] = line % 2 == 0 ? 1 : -1;
      }
      a = e;
    }
    line += any;
  }
  return out;
}

}  // namespace

std::vector<uint8_t> highway_costs(const Graph& g, const HighwayOptions& opt)
{
  if (!g.is_grid() || opt.penalty <= 0 || g.size() == 0) return {};
  const auto gx = grains(g, 0, std::max(opt.min_run, 1)), gy = grains(g, 1, std::max(opt.min_run, 1));
  std::vector<uint8_t> cost(g.num_arcs(), 0);
  const uint8_t p = static_cast<uint8_t>(std::min(opt.penalty, 200));
  bool any = false;
  for (Vertex u = 0; u < g.size(); ++u) {
    const auto in = g.in_neighbors(u);
    for (size_t k = 0; k < in.size(); ++k) {
      const Vertex w = in[k];
      const int dx = g.cell_x(u) - g.cell_x(w), dy = g.cell_y(u) - g.cell_y(w);
      int8_t grain = 0;
      int step = 0;
      if (dy == 0 && gx[w] != 0 && gx[u] == gx[w]) grain = gx[u], step = dx;
      else if (dx == 0 && gy[w] != 0 && gy[u] == gy[w]) grain = gy[u], step = dy;
      // Only a move whose reverse exists has a choice to steer: a one-way arc (a directed
      // graph) is the only way through and keeps its cost.
      if (grain != 0 && step != grain && g.adjacent(u, w)) {
        cost[g.in_arc(u) + k] = p;
        any = true;
      }
    }
  }
  if (!any) return {};
  return cost;
}

}  // namespace planner
