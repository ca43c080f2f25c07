#pragma once
// Tiny test grids from strings, shared by the planner, policy and task-layer tests.
#include <string>
#include <vector>

#include "planner/graph.hpp"
#include "planner/rng.hpp"

namespace test {

// '.' free, anything else blocked; all rows the same width.
inline planner::Graph grid(const std::vector<std::string>& rows)
{
  const int h = static_cast<int>(rows.size()), w = static_cast<int>(rows.at(0).size());
  std::vector<bool> free(static_cast<size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) free[static_cast<size_t>(y) * w + x] = rows[y].at(x) == '.';
  return planner::Graph::from_grid(w, h, free);
}

// A random w x h grid with about `pct` % obstacles (seeded), its free cells connected or not.
inline planner::Graph random_grid(int w, int h, int pct, uint64_t seed)
{
  planner::Rng rng(seed);
  std::vector<std::string> rows(static_cast<size_t>(h), std::string(static_cast<size_t>(w), '.'));
  for (auto& r : rows)
    for (auto& c : r)
      if (rng.below(100) < static_cast<uint32_t>(pct)) c = '@';
  return grid(rows);
}

// Every vertex of g in an order shuffled by rng: distinct random starts (and goals).
inline std::vector<planner::Vertex> shuffled_cells(const planner::Graph& g, planner::Rng& rng)
{
  std::vector<planner::Vertex> cells;
  for (planner::Vertex v = 0; v < g.size(); ++v) cells.push_back(v);
  rng.shuffle(cells.data(), static_cast<int>(cells.size()));
  return cells;
}

// A random vertex other than `from` in its component (`comp`: g.components()): a lifelong
// robot's next goal.
inline planner::Vertex random_goal(const planner::Graph& g, const std::vector<int>& comp, planner::Rng& rng,
                                   planner::Vertex from)
{
  for (;;) {
    const auto v = static_cast<planner::Vertex>(rng.below(static_cast<uint32_t>(g.size())));
    if (v != from && comp[v] == comp[from]) return v;
  }
}

// Pocket labels as set_pockets takes them (-1 outside any pocket): `cells` form one dead-end
// pocket labelled by its station `label`.
inline std::vector<planner::Vertex> pocket_labels(const planner::Graph& g, const std::vector<planner::Vertex>& cells,
                                                  planner::Vertex label)
{
  std::vector<planner::Vertex> pocket(static_cast<size_t>(g.size()), -1);
  for (planner::Vertex v : cells) pocket[static_cast<size_t>(v)] = label;
  return pocket;
}

}  // namespace test
