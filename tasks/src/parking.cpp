#include "tasks/parking.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tasks {

Parking::Parking(const planner::Graph& g, std::vector<planner::Vertex> cells)
    : g_(g), parking_(g.size(), 0), claimed_by_(g.size(), -1), seen_(g.size(), 0)
{
  // As Battery's chargers: a cell off the graph indexed the tables below out of bounds (heap
  // corruption from Python's lifelong(parking=[-3])).
  for (planner::Vertex v : cells)
    if (v < 0 || v >= g.size())
      throw std::invalid_argument("parking: cell " + std::to_string(v) + " is not a vertex of the graph (0.." +
                                  std::to_string(g.size() - 1) + ")");
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  cells_ = std::move(cells);
  for (planner::Vertex v : cells_) parking_[v] = 1;
  free_parking_ = static_cast<int>(cells_.size());
}

template <class Ok>
planner::Vertex Parking::nearest(planner::Vertex from, Ok ok)
{
  ++stamp_;
  std::vector<planner::Vertex> open{from};
  seen_[from] = stamp_;
  for (size_t i = 0; i < open.size(); ++i) {
    const planner::Vertex v = open[i];
    if (claimed_by_[v] < 0 && ok(v)) return v;
    for (planner::Vertex u : g_.neighbors(v))
      if (seen_[u] != stamp_) {
        seen_[u] = stamp_;
        open.push_back(u);
      }
  }
  return -1;
}

void Parking::apply(const std::vector<char>& idle, const planner::Config& positions, const std::vector<uint8_t>* reserved,
                    planner::Config& goals, const std::vector<uint8_t>* in_use)
{
  const int n = static_cast<int>(idle.size());
  if (static_cast<int>(claim_.size()) != n) claim_.assign(n, -1), sent_.assign(n, 0);
  auto release = [&](int a) {
    if (claim_[a] < 0) return;
    if (parking_[claim_[a]]) ++free_parking_;
    claimed_by_[claim_[a]] = -1;
    claim_[a] = -1;
    sent_[a] = 0;
  };
  auto take = [&](int a, planner::Vertex v) {
    claim_[a] = v;
    sent_[a] = parking_[v] || v != positions[a];
    claimed_by_[v] = a;
    if (parking_[v]) --free_parking_;
  };
  for (int a = 0; a < n; ++a)
    if (!idle[a]) release(a);
  // A parking cell on the cells of a station in use (a station queue laid along a parking
  // lane) is no place to wait: an agent parked there blocks the queue it lies on, so it leaves.
  // Traced on large_warehouse_parking (session 36): pickup0's queue ran down the parking lane,
  // idle AGVs parked on every other queue cell, and pickup0's errands stalled for the whole run.
  auto parkable = [&](planner::Vertex u) { return parking_[u] != 0 && !(in_use && (*in_use)[u]); };
  for (int a = 0; a < n; ++a)
    if (claim_[a] >= 0 && parking_[claim_[a]] && !parkable(claim_[a])) release(a);
  // Idle agents already on an unclaimed parking cell keep it, so nobody else is sent there.
  for (int a = 0; a < n; ++a)
    if (idle[a] && claim_[a] < 0 && parkable(positions[a]) && claimed_by_[positions[a]] < 0) take(a, positions[a]);
  for (int a = 0; a < n; ++a) {
    if (!idle[a]) continue;
    if (claim_[a] < 0) {
      planner::Vertex v = -1;
      if (free_parking_ > 0) v = nearest(positions[a], parkable);
      if (v < 0) v = nearest(positions[a], [&](planner::Vertex u) { return !reserved || !(*reserved)[u]; });
      if (v >= 0) take(a, v);
    }
    goals[a] = claim_[a] >= 0 ? claim_[a] : positions[a];
  }
}

}  // namespace tasks
