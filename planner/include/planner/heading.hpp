#pragma once
// Heading: the rotation action model's geometry, written once (LoRR's MAPF_T, after the
// Start-Kit's ActionModelWithRotate::result_state). Every layer that turns robots uses it:
// the rotation planners, their distance tables, guidance, the rotation executor, the
// heading preference, the LoRR log checker and the SUMO controller.
//
// Headings are LoRR's: 0 east (+x), 1 south (+y), 2 west, 3 north; clockwise is +1. Actions:
// F moves one cell ahead, R turns clockwise, C counter-clockwise, W waits; each takes one
// step and a turn keeps the robot on its cell.
#include <stdexcept>
#include <string>

#include "planner/graph.hpp"

namespace planner {

constexpr int kHeadingDx[4] = {1, 0, -1, 0};
constexpr int kHeadingDy[4] = {0, 1, 0, -1};
constexpr char kHeadingLetter[4] = {'E', 'S', 'W', 'N'};

constexpr int turned_cw(int h) { return (h + 1) % 4; }
constexpr int turned_ccw(int h) { return (h + 3) % 4; }
constexpr int reversed(int h) { return (h + 2) % 4; }
// The heading after `action` (R, C: a quarter turn; F, W and anything else: unchanged).
constexpr int heading_after(int h, char action) { return action == 'R' ? turned_cw(h) : action == 'C' ? turned_ccw(h) : h; }
// Quarter turns between two headings (0, 1 or 2).
constexpr int quarter_turns(int from, int to) { return (to - from + 4) % 4 == 3 ? 1 : (to - from + 4) % 4; }
// The turn that brings heading h nearer to d (h != d): 'R' (clockwise) or 'C'. A half turn
// goes clockwise.
constexpr char turn_toward(int h, int d) { return (d - h + 4) % 4 == 3 ? 'C' : 'R'; }

// The cell ahead of v facing h on a grid graph, if the graph has the move v -> it; -1 off
// the map, on an obstacle, or against a one-way arc (a directed graph; and on a gridified
// net two cells side by side are not always joined).
inline Vertex cell_ahead(const Graph& g, Vertex v, int h)
{
  const Vertex u = g.at(g.cell_x(v) + kHeadingDx[h], g.cell_y(v) + kHeadingDy[h]);
  return u >= 0 && g.adjacent(v, u) ? u : -1;
}
// The cell behind v facing h from which a forward move (heading h) enters v; -1 if none. The
// backward searches (distance tables) walk these: on a directed graph it is not the cell
// ahead facing the other way.
inline Vertex cell_behind(const Graph& g, Vertex v, int h)
{
  const Vertex u = g.at(g.cell_x(v) - kHeadingDx[h], g.cell_y(v) - kHeadingDy[h]);
  return u >= 0 && g.adjacent(u, v) ? u : -1;
}

// The heading of the move u -> v between 4-neighbours of a grid graph; throws
// std::invalid_argument for anything else.
inline int heading_of_move(const Graph& g, Vertex u, Vertex v)
{
  const int dx = g.cell_x(v) - g.cell_x(u), dy = g.cell_y(v) - g.cell_y(u);
  for (int h = 0; h < 4; ++h)
    if (dx == kHeadingDx[h] && dy == kHeadingDy[h]) return h;
  throw std::invalid_argument("not a 4-neighbour move: " + std::to_string(u) + " -> " + std::to_string(v));
}

// A robot's state under the rotation model.
struct Pose {
  Vertex v = -1;
  int heading = 0;
  bool operator==(const Pose& o) const { return v == o.v && heading == o.heading; }
};

// The state after `action` (ActionModelWithRotate::result_state): F into the cell ahead
// (v = -1 when there is none), turns in place, W (and anything else) unchanged.
inline Pose result_state(const Graph& g, Pose s, char action)
{
  if (action == 'F') return {cell_ahead(g, s.v, s.heading), s.heading};
  return {s.v, heading_after(s.heading, action)};
}

}  // namespace planner
