#include "planner/blocked.hpp"

#include <stdexcept>

namespace planner {

Graph without_arcs(const Graph& g, const std::function<bool(Vertex, Vertex)>& drop)
{
  std::vector<std::pair<Vertex, Vertex>> arcs;
  arcs.reserve(g.num_arcs());
  for (Vertex u = 0; u < g.size(); ++u)
    for (Vertex v : g.neighbors(u))
      if (!drop(u, v)) arcs.emplace_back(u, v);
  std::vector<Point> pos;
  if (g.has_positions())
    for (Vertex v = 0; v < g.size(); ++v) pos.push_back(g.position(v));
  Graph out = Graph::from_arcs(g.size(), arcs, std::move(pos));
  if (g.is_grid()) {
    std::vector<int32_t> cells(g.size());
    for (Vertex v = 0; v < g.size(); ++v) cells[v] = g.cell_y(v) * g.width() + g.cell_x(v);
    out.attach_grid(g.width(), g.height(), std::move(cells));
  }
  out.name = g.name;
  if (g.weighted()) out.set_move_costs(g.move_costs());  // a slow lane stays slow
  return out;
}

std::vector<int32_t> exit_distance(const Graph& g, const std::vector<uint8_t>& blocked)
{
  if (blocked.size() != static_cast<size_t>(g.size()))
    throw std::invalid_argument("blocked: one entry per vertex needed");
  // Multi-source BFS backwards (in-neighbours) from every unblocked vertex.
  std::vector<int32_t> d(g.size(), -1);
  std::vector<Vertex> queue;
  for (Vertex v = 0; v < g.size(); ++v)
    if (!blocked[v]) d[v] = 0, queue.push_back(v);
  for (size_t h = 0; h < queue.size(); ++h) {
    const Vertex v = queue[h];
    for (Vertex u : g.in_neighbors(v))
      if (d[u] < 0) d[u] = d[v] + 1, queue.push_back(u);
  }
  return d;
}

Graph blocked_graph(const Graph& g, const std::vector<uint8_t>& blocked)
{
  const std::vector<int32_t> d = exit_distance(g, blocked);
  return without_arcs(g, [&](Vertex u, Vertex v) {
    if (!blocked[v]) return false;
    // Into a blocked vertex: only from inside the region and one step nearer its exit.
    return !blocked[u] || d[v] < 0 || d[u] < 0 || d[v] >= d[u];
  });
}

}  // namespace planner
