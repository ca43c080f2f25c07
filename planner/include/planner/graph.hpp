#pragma once
// Graph: the MAPF graph. Vertices are dense ids 0..size()-1. A move follows an arc u -> v;
// most graphs are undirected (every arc has its reverse), but a warehouse with one-way
// aisles is directed (from_arcs). neighbors(v) are the out-neighbours (the moves out of v,
// what PIBT and LaCAM generate successors from); in_neighbors(v) the in-neighbours (what a
// distance-to-goal BFS walks, since it runs backwards from the goal). On an undirected
// graph both are the same list. Neighbour lists are stored flat (CSR) because PIBT walks
// them in its innermost loop.
//
// Which planners accept a directed graph, and with which guarantee, is stated in
// lacam/lacam.hpp and lacam/rt_lacam.hpp; the rotation planners move along the arcs
// (rotation/rotation_dist.hpp), with no completeness on any graph.
//
// Vertices may carry a display position (x, y). Graphs built from a MovingAI grid also
// keep the grid: width(), height(), cell (x = column, y = row) of each vertex and the
// vertex at a cell (-1 on obstacles).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace planner {

using Vertex = int32_t;

struct Point {
  double x = 0, y = 0;
};

// A read-only view of a contiguous range (C++17 has no std::span).
template <class T>
struct Span {
  const T* b = nullptr;
  const T* e = nullptr;
  const T* begin() const { return b; }
  const T* end() const { return e; }
  size_t size() const { return static_cast<size_t>(e - b); }
  bool empty() const { return b == e; }
  const T& operator[](size_t k) const { return b[k]; }
};

class Graph {
 public:
  Graph() = default;

  // Undirected graph from an edge list. Duplicate edges are merged; self-loops and
  // ids out of range throw std::invalid_argument. `pos` is empty or has one entry per vertex.
  static Graph from_edges(int num_vertices, const std::vector<std::pair<Vertex, Vertex>>& edges,
                          std::vector<Point> pos = {});

  // Directed graph from arcs u -> v (a two-way edge is given as both arcs). Same checks as
  // from_edges. If every arc has its reverse the result is undirected (directed() false).
  static Graph from_arcs(int num_vertices, const std::vector<std::pair<Vertex, Vertex>>& arcs,
                         std::vector<Point> pos = {});

  // 4-connected grid graph; free[y * width + x] says whether the cell is free.
  static Graph from_grid(int width, int height, const std::vector<bool>& free);

  int size() const { return static_cast<int>(offsets_.size()) - 1; }
  // Out-neighbours: the vertices a move from v may go to.
  Span<Vertex> neighbors(Vertex v) const { return {nbrs_.data() + offsets_[v], nbrs_.data() + offsets_[v + 1]}; }
  // In-neighbours: the vertices with a move to v (== neighbors(v) on an undirected graph).
  Span<Vertex> in_neighbors(Vertex v) const
  {
    return directed_ ? Span<Vertex>{in_nbrs_.data() + in_offsets_[v], in_nbrs_.data() + in_offsets_[v + 1]} : neighbors(v);
  }
  // Index of v's first in-arc among all num_arcs() in-arcs, numbered in in-neighbour order:
  // in-arc k of v (from in_neighbors(v)[k]) is in_arc(v) + k. Per-arc data (DistCache's arc
  // costs) is indexed so.
  size_t in_arc(Vertex v) const { return static_cast<size_t>(directed_ ? in_offsets_[v] : offsets_[v]); }
  int degree(Vertex v) const { return offsets_[v + 1] - offsets_[v]; }  // out-degree
  int max_degree() const { return max_degree_; }
  bool adjacent(Vertex u, Vertex v) const;  // is there an arc u -> v (a legal move)?
  // Undirected edges: a two-way pair of arcs counts once, a one-way arc once.
  size_t num_edges() const { return (nbrs_.size() + one_way_) / 2; }
  size_t num_arcs() const { return nbrs_.size(); }
  size_t num_one_way() const { return one_way_; }  // arcs without their reverse
  // True if some arc has no reverse: a move there cannot be undone by the reverse move.
  bool directed() const { return directed_; }

  bool has_positions() const { return !pos_.empty(); }
  Point position(Vertex v) const { return pos_[v]; }

  // Grid graphs only (width() == 0 otherwise).
  bool is_grid() const { return width_ > 0; }
  int width() const { return width_; }
  int height() const { return height_; }
  Vertex at(int x, int y) const;              // -1 off the map or on an obstacle
  int cell_x(Vertex v) const { return cell_[v] % width_; }
  int cell_y(Vertex v) const { return cell_[v] / width_; }

  // Gives a graph built from an edge list the grid view of a lattice: vertex v sits at
  // cell (cells[v] % width, cells[v] / width). Throws std::invalid_argument unless the
  // cells are distinct and inside the grid and every edge joins 4-neighbours (a
  // gridified warehouse whose aisles lie on a lattice becomes a grid graph this way).
  void attach_grid(int width, int height, std::vector<int32_t> cells);

  // Number of connected components and a component id per vertex (arcs taken as
  // undirected: weakly connected components of a directed graph).
  std::vector<int> components(int* count = nullptr) const;

  // Strongly connected components (each vertex reaches every other of its component) and
  // their count; equal to components() on an undirected graph. Vertices with blocked[v]
  // != 0 (optional, one entry per vertex) are left out: component -1.
  std::vector<int> strong_components(int* count = nullptr, const std::vector<uint8_t>* blocked = nullptr) const;

  // Whether `to` can be reached from `from` along arcs.
  bool reaches(Vertex from, Vertex to) const;

  // Move costs (optional): a move onto v costs move_cost(v) >= 1, e.g. the ticks an AGV
  // needs to enter a cell of a slow lane. Only the distance tables read them (DistCache:
  // the heuristics PIBT and LaCAM rank moves by); the search space, the validator and a
  // plan's steps do not change, so no guarantee does. Without costs (the default) every
  // move costs 1 and the tables are plain BFS. Throws std::invalid_argument unless there
  // is one cost per vertex, each >= 1; all 1: no costs (weighted() false).
  void set_move_costs(std::vector<uint8_t> costs);
  bool weighted() const { return !cost_.empty(); }
  int32_t move_cost(Vertex v) const { return cost_.empty() ? 1 : cost_[v]; }
  int32_t max_move_cost() const { return max_cost_; }
  const std::vector<uint8_t>& move_costs() const { return cost_; }  // empty: all 1

  std::string name;  // e.g. the map file it came from

 private:
  std::vector<int32_t> offsets_{0};
  std::vector<Vertex> nbrs_;
  std::vector<int32_t> in_offsets_;  // directed graphs only: in-neighbour lists (CSR)
  std::vector<Vertex> in_nbrs_;
  bool directed_ = false;
  size_t one_way_ = 0;
  std::vector<Point> pos_;
  int max_degree_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<int32_t> cell_;       // vertex -> y * width + x
  std::vector<Vertex> vertex_at_;   // y * width + x -> vertex or -1
  std::vector<uint8_t> cost_;       // move costs, empty: all 1
  int32_t max_cost_ = 1;
};

}  // namespace planner
