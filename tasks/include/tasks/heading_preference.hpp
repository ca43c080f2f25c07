#pragma once
// HeadingPreference: PIBT's move order for the rotation model. Under LoRR's MAPF_T a move
// that is not straight ahead costs a step per quarter turn first, which cell-space PIBT
// does not see: among moves that bring an agent equally near its goal it picks at random
// and the robots zigzag. This preference keeps PIBT's order by distance to goal and breaks
// ties by the quarter turns the move needs from the robot's heading at the plan frontier
// (the direction of its last planned move). Scores stay below the next distance, so no
// move that gets nearer is ever traded for a straighter one.
//
// Headings are known for the frontier configuration only (the root of RT-LaCAM's tree,
// where next() takes the step); deeper in the tree PIBT gets plain distances.
#include <vector>

#include "planner/action_preference.hpp"
#include "planner/dist_table.hpp"

namespace tasks {

class HeadingPreference : public planner::ActionPreference {
 public:
  HeadingPreference(const planner::Graph& g, const planner::Config& starts);
  void set_goals(const planner::Config& goals) override { dist_.set_goals(goals); }
  float score(int agent, planner::Vertex from, planner::Vertex to, planner::Rng& rng) override;
  // The planner committed `next`: headings follow the planned moves.
  void committed(const planner::Config& next);
  void set_max_dist_tables(size_t n) { dist_.set_max_tables(n); }

 private:
  const planner::Graph& g_;
  planner::DistTable dist_;
  planner::Config at_;      // frontier cell of each robot
  std::vector<int> heading_;
};

}  // namespace tasks
