#pragma once
// Parking: where an agent without a task waits (issue 24, "parking and queues").
//
// An idle agent claims the nearest unclaimed parking cell (breadth-first along arcs from
// where it stands) and heads there; it keeps the claim until it gets a task. With no
// parking cell left it stays where it stands -- unless that cell is `reserved` (a
// station, a station's dead-end pocket or a queue cell: tasks/station_queues.hpp), where
// it would block the station: then it claims the nearest cell that is neither reserved
// nor claimed. A parking cell on the cells of a station in use (its queue laid along a parking
// lane: `in_use`, StationQueues::in_use_cells) is not used, and an agent parked there leaves:
// it would block the queue it stands on. Claims keep two idle agents off one cell. Without parking an idle agent
// stands wherever its last errand ended: in an aisle, or in a dead-end station that the
// next agent sent there cannot enter (no swaps).
//
// Goals change only when the task manager calls apply() (its start() and update()).
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace tasks {

// Parking of a run (task_layer.hpp): off, or on with its cells (empty: idle agents only
// leave reserved cells).
struct ParkingOptions {
  bool on = false;
  std::vector<planner::Vertex> cells;
};

class Parking {
 public:
  // `cells`: the parking cells (may be empty: then only the reserved-cell rule applies).
  Parking(const planner::Graph& g, std::vector<planner::Vertex> cells);

  // idle[a]: agent a holds no task. Sets goals[a] of the idle agents; `reserved` (per
  // vertex, may be null) are the cells an idle agent must not stay on; `in_use` (per vertex,
  // may be null) the parking cells not to park on now.
  void apply(const std::vector<char>& idle, const planner::Config& positions, const std::vector<uint8_t>* reserved,
             planner::Config& goals, const std::vector<uint8_t>* in_use = nullptr);

  bool is_parking(planner::Vertex v) const { return parking_[v] != 0; }
  // Agent a was sent somewhere: to a parking cell, or off a reserved cell. An agent that
  // just stays where it stood is not (tasks/task_manager.hpp: not awaited, as without parking).
  bool sent(int a) const { return a < static_cast<int>(sent_.size()) && sent_[a]; }
  const std::vector<planner::Vertex>& cells() const { return cells_; }

 private:
  // Nearest cell from `from` (BFS along arcs) that nobody claimed and `ok` accepts; -1: none.
  template <class Ok>
  planner::Vertex nearest(planner::Vertex from, Ok ok);

  const planner::Graph& g_;
  std::vector<planner::Vertex> cells_;
  std::vector<uint8_t> parking_;
  std::vector<int> claim_;       // per agent: claimed cell, -1
  std::vector<char> sent_;       // per agent: the claim is a parking cell or away from a reserved cell
  std::vector<int> claimed_by_;  // per vertex: agent, -1
  int free_parking_ = 0;         // parking cells nobody claims
  std::vector<int> seen_;        // BFS marks (stamp per search)
  int stamp_ = 0;
};

}  // namespace tasks
