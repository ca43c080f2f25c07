#include "planner/graph.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace planner {

Graph Graph::from_edges(int n, const std::vector<std::pair<Vertex, Vertex>>& edges, std::vector<Point> pos)
{
  std::vector<std::pair<Vertex, Vertex>> arcs;
  arcs.reserve(edges.size() * 2);
  for (auto [u, v] : edges) {
    arcs.emplace_back(u, v);
    arcs.emplace_back(v, u);
  }
  return from_arcs(n, arcs, std::move(pos));
}

Graph Graph::from_arcs(int n, const std::vector<std::pair<Vertex, Vertex>>& arcs_in, std::vector<Point> pos)
{
  if (n < 0) throw std::invalid_argument("graph: negative vertex count");
  if (!pos.empty() && static_cast<int>(pos.size()) != n)
    throw std::invalid_argument("graph: " + std::to_string(pos.size()) + " positions for " + std::to_string(n) + " vertices");
  std::vector<std::pair<Vertex, Vertex>> arcs;
  arcs.reserve(arcs_in.size());
  for (auto [u, v] : arcs_in) {
    if (u < 0 || v < 0 || u >= n || v >= n)
      throw std::invalid_argument("graph: edge (" + std::to_string(u) + "," + std::to_string(v) + ") out of range");
    if (u == v) throw std::invalid_argument("graph: self-loop at vertex " + std::to_string(u));
    arcs.emplace_back(u, v);
  }
  std::sort(arcs.begin(), arcs.end());
  arcs.erase(std::unique(arcs.begin(), arcs.end()), arcs.end());

  Graph g;
  g.offsets_.assign(n + 1, 0);
  for (auto& a : arcs) ++g.offsets_[a.first + 1];
  for (int v = 0; v < n; ++v) g.offsets_[v + 1] += g.offsets_[v];
  g.nbrs_.resize(arcs.size());
  for (size_t k = 0; k < arcs.size(); ++k) g.nbrs_[k] = arcs[k].second;  // arcs sorted by source
  for (int v = 0; v < n; ++v) g.max_degree_ = std::max(g.max_degree_, g.degree(v));
  for (auto [u, v] : arcs) g.one_way_ += !g.adjacent(v, u);
  g.directed_ = g.one_way_ > 0;
  if (g.directed_) {  // in-lists: the arcs sorted by target
    std::vector<std::pair<Vertex, Vertex>> rev;
    rev.reserve(arcs.size());
    for (auto [u, v] : arcs) rev.emplace_back(v, u);
    std::sort(rev.begin(), rev.end());
    g.in_offsets_.assign(n + 1, 0);
    for (auto& a : rev) ++g.in_offsets_[a.first + 1];
    for (int v = 0; v < n; ++v) g.in_offsets_[v + 1] += g.in_offsets_[v];
    g.in_nbrs_.resize(rev.size());
    for (size_t k = 0; k < rev.size(); ++k) g.in_nbrs_[k] = rev[k].second;
  }
  g.pos_ = std::move(pos);
  return g;
}

Graph Graph::from_grid(int width, int height, const std::vector<bool>& free)
{
  if (width <= 0 || height <= 0 || free.size() != static_cast<size_t>(width) * height)
    throw std::invalid_argument("graph: bad grid dimensions");
  std::vector<Vertex> vertex_at(free.size(), -1);
  std::vector<int32_t> cell;
  std::vector<Point> pos;
  for (int k = 0; k < width * height; ++k) {
    if (!free[k]) continue;
    vertex_at[k] = static_cast<Vertex>(cell.size());
    cell.push_back(k);
    pos.push_back({static_cast<double>(k % width), static_cast<double>(k / width)});
  }
  std::vector<std::pair<Vertex, Vertex>> edges;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      Vertex v = vertex_at[y * width + x];
      if (v < 0) continue;
      if (x + 1 < width && vertex_at[y * width + x + 1] >= 0) edges.emplace_back(v, vertex_at[y * width + x + 1]);
      if (y + 1 < height && vertex_at[(y + 1) * width + x] >= 0) edges.emplace_back(v, vertex_at[(y + 1) * width + x]);
    }
  }
  Graph g = from_edges(static_cast<int>(cell.size()), edges, std::move(pos));
  g.width_ = width;
  g.height_ = height;
  g.cell_ = std::move(cell);
  g.vertex_at_ = std::move(vertex_at);
  return g;
}

void Graph::attach_grid(int width, int height, std::vector<int32_t> cells)
{
  if (width <= 0 || height <= 0 || cells.size() != static_cast<size_t>(size()))
    throw std::invalid_argument("graph: grid view needs one cell per vertex");
  std::vector<Vertex> vertex_at(static_cast<size_t>(width) * height, -1);
  for (Vertex v = 0; v < size(); ++v) {
    if (cells[v] < 0 || cells[v] >= width * height) throw std::invalid_argument("graph: cell off the grid");
    if (vertex_at[cells[v]] >= 0) throw std::invalid_argument("graph: two vertices on one cell");
    vertex_at[cells[v]] = v;
  }
  for (Vertex v = 0; v < size(); ++v)
    for (Vertex u : neighbors(v)) {
      const int dx = std::abs(cells[u] % width - cells[v] % width), dy = std::abs(cells[u] / width - cells[v] / width);
      if (dx + dy != 1) throw std::invalid_argument("graph: an edge joins cells that are not 4-neighbours");
    }
  width_ = width;
  height_ = height;
  cell_ = std::move(cells);
  vertex_at_ = std::move(vertex_at);
}

bool Graph::adjacent(Vertex u, Vertex v) const
{
  auto nb = neighbors(u);
  return std::binary_search(nb.begin(), nb.end(), v);  // lists are sorted by construction
}

Vertex Graph::at(int x, int y) const
{
  if (!is_grid() || x < 0 || y < 0 || x >= width_ || y >= height_) return -1;
  return vertex_at_[y * width_ + x];
}

std::vector<int> Graph::components(int* count) const
{
  std::vector<int> comp(size(), -1);
  std::vector<Vertex> stack;
  int c = 0;
  for (Vertex s = 0; s < size(); ++s) {
    if (comp[s] >= 0) continue;
    comp[s] = c;
    stack.push_back(s);
    while (!stack.empty()) {
      Vertex v = stack.back();
      stack.pop_back();
      for (Vertex u : neighbors(v))
        if (comp[u] < 0) comp[u] = c, stack.push_back(u);
      for (Vertex u : in_neighbors(v))  // weak components: arcs both ways
        if (comp[u] < 0) comp[u] = c, stack.push_back(u);
    }
    ++c;
  }
  if (count) *count = c;
  return comp;
}

std::vector<int> Graph::strong_components(int* count, const std::vector<uint8_t>* blocked) const
{
  // Kosaraju, iteratively (a recursive DFS overflows the stack on 10^5-cell aisles):
  // finish order of a DFS over out-arcs, then components by DFS over in-arcs in reverse
  // finish order.
  const int n = size();
  auto off = [&](Vertex v) { return blocked && (*blocked)[v]; };
  std::vector<Vertex> order;
  order.reserve(n);
  std::vector<uint8_t> seen(n, 0);
  std::vector<std::pair<Vertex, int>> stack;  // vertex, index of the next out-neighbour
  for (Vertex s = 0; s < n; ++s) {
    if (seen[s] || off(s)) continue;
    seen[s] = 1;
    stack.emplace_back(s, 0);
    while (!stack.empty()) {
      auto& [v, k] = stack.back();
      const auto nb = neighbors(v);
      if (k < static_cast<int>(nb.size())) {
        const Vertex u = nb[k++];
        if (!seen[u] && !off(u)) seen[u] = 1, stack.emplace_back(u, 0);
      } else {
        order.push_back(v);
        stack.pop_back();
      }
    }
  }
  std::vector<int> comp(n, -1);
  std::vector<Vertex> todo;
  int c = 0;
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    if (comp[*it] >= 0) continue;
    comp[*it] = c;
    todo.assign(1, *it);
    while (!todo.empty()) {
      const Vertex v = todo.back();
      todo.pop_back();
      for (Vertex u : in_neighbors(v))
        if (comp[u] < 0 && !off(u)) comp[u] = c, todo.push_back(u);
    }
    ++c;
  }
  if (count) *count = c;
  return comp;
}

bool Graph::reaches(Vertex from, Vertex to) const
{
  std::vector<uint8_t> seen(size(), 0);
  std::vector<Vertex> todo{from};
  seen[from] = 1;
  while (!todo.empty()) {
    const Vertex v = todo.back();
    todo.pop_back();
    if (v == to) return true;
    for (Vertex u : neighbors(v))
      if (!seen[u]) seen[u] = 1, todo.push_back(u);
  }
  return false;
}

void Graph::set_move_costs(std::vector<uint8_t> costs)
{
  if (costs.size() != static_cast<size_t>(size()))
    throw std::invalid_argument("move costs: " + std::to_string(costs.size()) + " for " + std::to_string(size()) + " vertices");
  int32_t top = 1;
  for (size_t v = 0; v < costs.size(); ++v) {
    if (costs[v] < 1) throw std::invalid_argument("move costs: vertex " + std::to_string(v) + " costs 0 (must be >= 1)");
    top = std::max<int32_t>(top, costs[v]);
  }
  max_cost_ = top;
  if (top == 1) costs.clear();  // all 1: the plain BFS tables
  cost_ = std::move(costs);
}

}  // namespace planner
