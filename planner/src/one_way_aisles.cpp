#include "planner/one_way_aisles.hpp"

#include <map>
#include <stdexcept>
#include <string>

#include "planner/blocked.hpp"

namespace planner {

Graph one_way_aisles(const Graph& g)
{
  if (!g.is_grid()) throw std::invalid_argument("one_way_aisles: '" + g.name + "' is not a grid graph");
  const int W = g.width(), H = g.height();
  // A shelf: blocked and inside the frame (the frame would make the border rows aisles).
  auto shelf = [&](int x, int y) { return x > 0 && y > 0 && x < W - 1 && y < H - 1 && g.at(x, y) < 0; };
  auto beside_shelf = [&](int x, int y) { return shelf(x, y - 1) || shelf(x, y + 1); };
  std::map<int, int> row_index;  // y of a row with aisle edges -> its rank, top to bottom
  for (int y = 0; y < H; ++y)
    for (int x = 0; x + 1 < W; ++x)
      if (g.at(x, y) >= 0 && g.at(x + 1, y) >= 0 && beside_shelf(x, y) && beside_shelf(x + 1, y)) {
        row_index.emplace(y, 0);
        break;
      }
  if (row_index.empty()) throw std::invalid_argument("one_way_aisles: '" + g.name + "' has no aisle between shelves");
  int k = 0;
  for (auto& [y, rank] : row_index) rank = k++;
  // An aisle arc is kept in its row's direction only: east (x + 1) on even rows.
  Graph d = without_arcs(g, [&](Vertex v, Vertex u) {
    const int x = g.cell_x(v), y = g.cell_y(v), ux = g.cell_x(u);
    const bool aisle = g.cell_y(u) == y && beside_shelf(x, y) && beside_shelf(ux, y);
    return aisle && (ux > x) != (row_index.at(y) % 2 == 0);
  });
  d.name = g.name + " (one-way aisles)";
  int count = 0;
  d.strong_components(&count);
  if (count != 1)
    throw std::invalid_argument("one_way_aisles: '" + g.name + "' with one-way aisles is not strongly connected (" +
                                std::to_string(count) + " components)");
  return d;
}

}  // namespace planner
