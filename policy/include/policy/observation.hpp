#pragma once
// Observation: what the policy sees of the world, one fixed-size float vector per agent --
// a (2r+1) x (2r+1) window of the grid centred on the agent, as in the SSIL line of work
// (Veerapaneni et al., "Work Smarter Not Harder", 2024). r is the model's radius (the
// weights file records it; the committed model uses r = 4, a 9x9 window).
//
// Tensor layout of one agent's observation, W = 2r+1, kChannels = 4 (C order, [c][row][col]):
//   obs[c * W*W + wy * W + wx]   for the cell (x, y) = (ax + wx - r, ay + wy - r),
// where (ax, ay) is the agent's cell (x = column, y = row; wy = 0 is the row above-most).
// Channels, for that cell:
//   0 obstacle      1 if the cell is blocked or off the map, else 0
//   1 agent         1 if another agent is there now, else 0 (the agent itself is not marked)
//   2 goal distance (d(cell) - d(agent cell)) / (2r), clipped to [-1, 1], where d is the
//                   agent's shortest-path distance to its goal (DistTable); 1 on blocked,
//                   off-map and unreachable cells (as far as it gets). Every value is a
//                   multiple of 1/(2r), so it quantises exactly (see dump_file.hpp).
//   3 parked agent  1 if another agent is there now and that cell is its goal, else 0
// A batch of n agents is an input_size x n column-major matrix: agent i's vector is the
// contiguous block [i * size(), (i+1) * size()).
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"

namespace policy {

constexpr int kChannels = 4;
enum Channel : int { kObstacle = 0, kAgent = 1, kGoalDistance = 2, kParked = 3 };

struct ObservationSpec {
  int radius = 4;
  int window() const { return 2 * radius + 1; }
  int size() const { return kChannels * window() * window(); }  // floats per agent
  int index(int c, int wx, int wy) const { return (c * window() + wy) * window() + wx; }
};

class ObservationBuilder {
 public:
  // `g` must be a grid graph (throws std::invalid_argument otherwise) and outlive this.
  ObservationBuilder(const planner::Graph& g, ObservationSpec spec);

  // Goal of each agent; distance tables are kept across calls (lifelong goal changes).
  void set_goals(const planner::Config& goals);
  const planner::Config& goals() const { return goals_; }
  const ObservationSpec& spec() const { return spec_; }

  // Observations of agents 0..n-1 (n == goals().size()) at `config`: n * spec().size()
  // floats written to `out`, agent after agent.
  void build(const planner::Vertex* config, int n, float* out);

 private:
  const planner::Graph& g_;
  ObservationSpec spec_;
  planner::DistTable dist_;
  planner::Config goals_;
  std::vector<int32_t> occ_;  // vertex -> agent there in the config being built, or -1
};

}  // namespace policy
