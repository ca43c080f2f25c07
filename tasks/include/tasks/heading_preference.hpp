#pragma once
// HeadingPreference: PIBT's move order for the rotation model. Under LoRR's MAPF_T a move
// that is not straight ahead costs a step per quarter turn first, which cell-space PIBT
// does not see: among moves that bring an agent equally near its goal it picks at random
// and the robots zigzag, and it does not count that a turn is a step spent in place.
//
// Two orders (HeadingCost):
//  - Ties: PIBT's order by distance to goal, ties broken by the quarter turns the move
//    needs (scores stay below the next distance: no move that gets nearer is traded for a
//    straighter one).
//  - Turns (default): the rotation-aware cost of the move, in steps, as WPPL's and Jiang et
//    al.'s rotation PIBT order candidates: the turns to face the move + 1 forward step +
//    the distance left from the next cell + the turns the robot will need there to face its
//    next shortest-path step (one turn of lookahead). Staying costs its step: 1 + the
//    distance and turns from where it is. So a robot facing a free shortest-path cell goes
//    straight, one that must turn prefers the move its heading makes cheapest, and a
//    detour that needs no turn can beat a turn. It needs only the cell distance tables
//    (shared with the planner, dist_cache.hpp): (cell, heading) tables would cost 4x the
//    memory, which LoRR's 10,000-agent WAREHOUSE cannot afford.
//
// Headings are known for the frontier configuration only (the root of RT-LaCAM's tree,
// where next() takes the step); deeper in the tree PIBT gets plain distances.
#include <memory>
#include <vector>

#include "planner/action_preference.hpp"
#include "planner/dist_table.hpp"

namespace tasks {

enum class HeadingCost { Ties, Turns };

class HeadingPreference : public planner::ActionPreference {
 public:
  HeadingPreference(const planner::Graph& g, const planner::Config& starts, HeadingCost cost = HeadingCost::Turns);
  void set_goals(const planner::Config& goals) override { dist_.set_goals(goals); }
  float score(int agent, planner::Vertex from, planner::Vertex to, planner::Rng& rng) override;
  // Prefetches the distances the turn lookahead reads (cells two steps from each robot at
  // its frontier cell; PIBT prefetches the candidates themselves): about half the cost of a
  // root expansion at 1,000 agents is waiting for them (docs/rotation_lorr.md).
  void prepare(const planner::Vertex* config, int n) override;
  // The planner committed `next`: headings follow the planned moves.
  void committed(const planner::Config& next);
  void set_max_dist_tables(size_t n) { dist_.set_max_tables(n); }
  // Distances from `cache`, the planner's: one BFS per goal for both (dist_cache.hpp).
  void share_dist_cache(std::shared_ptr<planner::DistCache> cache) { dist_.share(std::move(cache)); }

  // Steps for `agent` facing `heading` on v to reach its goal, to one turn of lookahead:
  // distance + the quarter turns to face its best next cell (0 on the goal).
  int32_t cost_to_go(int agent, planner::Vertex v, int heading);

 private:
  const planner::Graph& g_;
  planner::DistTable dist_;
  HeadingCost cost_;
  planner::Config at_;      // frontier cell of each robot
  std::vector<int> heading_;
};

}  // namespace tasks
