#pragma once
// RotationPibt (solver `pibt-rot`): PIBT over (cell, heading) states for the rotation
// action model (LoRR's MAPF_T; rotation_dist.hpp). Each step it gives every robot one
// action directly: F (forward into the cell ahead), R (turn clockwise), C (turn
// counter-clockwise) or W (wait). No cell plan and no adapter: a robot that must turn is
// planned as turning, so robots behind it are not held up by a plan that assumed it moves.
//
// The step (PIBT, Okumura et al. AIJ 2022, with candidates = actions):
//  - agents in descending priority; an undecided agent ranks its four actions by the exact
//    rotation-aware distance h of the state each leads to (RotationDist), ties: forward
//    first, then at random (a seeded Rng);
//  - occupancy is on cells: F reserves the cell ahead for the next step, R, C and W keep
//    the robot's cell; no two robots reserve one cell (no vertex conflict);
//  - priority inheritance: F into a cell whose robot has not decided yet asks that robot to
//    vacate it, which it can do only by F (turns and waits keep the cell); if it cannot,
//    it stays (its best turn or wait) and the asker tries its next action. A robot asked
//    by j never moves into j's cell (no swap). Following a robot that moves forward out of
//    the cell (and cycles of followers) is allowed, as in LoRR's ActionModelWithRotate,
//    which checks only vertex and swap conflicts.
//  - priorities: steps since the agent's goal was set, + h / 65536 at that time to break
//    ties (far first); on its goal an agent drops to that fraction (lowest).
// The design follows the rotation PIBT of WPPL (Jiang et al., "Scaling lifelong multi-agent
// path finding to more realistic settings", 2024; LoRR 2023 winner) and the LoRR start
// kit's PIBT (MIT), written anew here; neither's code is copied.
//
// Not RT-LaCAM: its reroot needs reversible moves (the old root one step from the new);
// a forward move has no one-step inverse. This is a one-step planner without a search
// tree: like PIBT it is not complete for one-shot MAPF (robots can livelock or deadlock,
// e.g. two robots facing each other in a corridor), which lifelong use tolerates and what
// LoRR entrants use. RT-LaCAM stays the planner for grid4. search() plans once per step;
// the budget is not needed (a step is O(agents) plus the BFS its new goals need).
#include <memory>
#include <string>
#include <vector>

#include "planner/realtime_planner.hpp"
#include "planner/rng.hpp"
#include "planner/rotation_dist.hpp"

namespace planner {

class RotationPibt : public RealtimePlanner {
 public:
  // All robots face `heading` (LoRR: east, 0) at the start. Needs a grid graph.
  RotationPibt(const Graph& g, const Config& starts, const Config& goals, uint64_t seed = 0, GoalTest test = {},
               int heading = 0);

  Status search(const Budget& b) override;
  const Config& next() override;  // the cells after the planned actions (turns keep the cell)
  void commit() override;
  void set_goals(const Config& goals, GoalTest test = {}) override;
  void set_max_dist_tables(size_t n) override { dist_.set_max_tables(n); }

  const Config& current() const override { return current_; }
  const Config& goals() const override { return goals_; }
  bool at_goal() const override { return passes_goal_test(test_, current_, goals_); }
  uint64_t expansions() const override { return steps_planned_; }
  size_t explored() const override { return 0; }
  std::string name() const override { return "pibt-rot"; }

  const std::vector<int>& headings() const { return heading_; }
  // The planned step's action per robot, one of "FRCW" (valid after search()).
  const std::string& actions() const { return action_; }
  uint16_t h(int agent) const { return dist_.get(goal_table_[agent], current_[agent], heading_[agent]); }
  const RotationDist& dist() const { return dist_; }

 private:
  bool pibt(int i, int asker);  // decides i's cell (decided_); asker: who asked i to vacate its cell
  bool moves(int i);            // may i's F go ahead now (memo_)

  const Graph& g_;
  mutable RotationDist dist_;
  Rng rng_;
  Config current_, goals_, next_;
  std::vector<int> heading_;
  GoalTest test_;
  std::vector<RotationDist::Table*> goal_table_;
  std::vector<double> prio_;
  std::vector<int32_t> order_;
  std::vector<int32_t> occ_now_, occ_next_;  // cell -> agent or -1
  std::vector<Vertex> decided_;               // per agent: its cell for this step's PIBT (-1: undecided)
  std::vector<Vertex> target_;                // per agent: the cell it turns toward (-1: none)
  std::vector<char> memo_;
  std::string action_;
  bool planned_ = false;
  uint64_t steps_planned_ = 0;
};

}  // namespace planner
