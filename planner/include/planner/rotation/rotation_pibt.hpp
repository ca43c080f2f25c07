#pragma once
// RotationPibt (solver `pibt-rot`): a one-step PIBT planner for robots with a heading, the
// rotation action model (LoRR's MAPF_T), on exact (cell, heading) distances (rotation_dist.hpp). Each step it gives every robot one
// action directly: F (forward into the cell ahead), R (turn clockwise), C (turn
// counter-clockwise) or W (wait). No cell plan and no adapter: a robot that must turn is
// planned as turning, so robots behind it are not held up by a plan that assumed it moves.
// Why not PIBT whose candidates are the four actions (tried first): a robot asked to vacate
// its cell can only do so by F, so one facing a wall can never be pushed and high-priority
// robots waited behind it for good (MR23-I-04: 0.36 errands/step).
//
// The step ("causal" PIBT, as in the LoRR 2024 start kit's default planner, MIT; written
// anew here, no code copied; ranking by exact (cell, heading) distances as WPPL's rotation
// PIBT does, Jiang et al. 2024, the LoRR 2023 winner):
//  1. PIBT (Okumura et al., AIJ 2022) decides a cell per robot: its own or a 4-neighbour,
//     ranked by the steps to the goal through it: quarter turns to face the neighbour + 1 +
//     h(neighbour, that heading) (RotationDist, exact), staying = 1 + h(cell, heading);
//     with guidance (set_guidance) each term in the guidance's costs instead of steps;
//     ties: straight ahead first, then at random (seeded). No two robots decide one cell;
//     priority inheritance as in PIBT: a robot that decides the cell of an undecided robot
//     asks it to vacate (it may not stay, nor take the asker's cell), else tries its next.
//  2. The decision becomes an action: the cell ahead -> F, a side or back cell -> turn
//     toward it (R, C; a half turn goes R), its own cell -> W.
//  3. F only if the cell ahead is free now or its robot leaves it forward in this step (and
//     not into this robot's cell: no swap); cycles of such robots go together. Else W.
//     So there are no vertex or swap conflicts on cells, turns keep the cell, and following
//     is allowed exactly as LoRR's ActionModelWithRotate allows it (it checks vertex and
//     swap conflicts only).
//  4. A robot turning toward its decided cell keeps it (reserved, not replanned) until it
//     gets there, or after waiting more than kPatience steps facing it: the turns already
//     spent are not thrown away by the next step's PIBT (re-deciding every step: 1.25 vs
//     1.49 errands/step on MR23-I-08, 2.49 vs 2.40 on I-04; docs/rotation_lorr.md).
//  Priorities: steps since the goal was set, + h / 65536 at that time (far first); on its
//  goal a robot drops to that fraction (lowest); +kDeadEndBoost per step in a dead end.
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

#include "planner/rng.hpp"
#include "planner/rotation/pocket_exit.hpp"
#include "planner/rotation/rotation_dist.hpp"
#include "planner/rotation/rotation_planner.hpp"

namespace planner {

class RotationPibt : public RotationPlanner {
 public:
  static constexpr int kPatience = 3;           // steps a robot facing its cell waits for it before choosing anew
  static constexpr double kDeadEndBoost = 10.0;  // priority per step in a dead end (away from the goal)

  // All robots face `heading` (LoRR: east, 0) at the start. Needs a grid graph.
  RotationPibt(const Graph& g, const Config& starts, const Config& goals, uint64_t seed = 0, GoalTest test = {},
               int heading = 0);

  Status search(const Budget& b) override;
  const Config& next() override;  // the cells after the planned actions (turns keep the cell)
  void commit() override;
  void set_goals(const Config& goals, GoalTest test = {}) override;
  void set_priority_hint(std::vector<float> hint) override { hint_ = std::move(hint); }  // applied at set_goals
  void set_max_dist_tables(size_t n) override { dist_.set_max_tables(n); }
  // Foreign pockets (RealtimePlanner::set_pockets, the cell PIBT's rule; tasks.urgency
  // pocket_cost): a move from outside into a dead-end pocket other than the robot's goal's
  // ranks `cost` forward moves worse. Staying and moves inside a pocket are never charged;
  // empty or 0: off (unchanged decisions). Why: on huge_warehouse_lifelong (1000 AGVs,
  // one-cell station stubs) PIBT pushed idle AGVs into stubs whose holders then stood in
  // the only way out; a robot in a one-cell stub cannot be pushed out past them (s34 trace).
  void set_pockets(std::vector<Vertex> pocket, float cost) override;
  // The pocket exit rule (pocket_exit.hpp; needs set_pockets' labels, any cost): no move
  // deeper into a dead-end pocket that a robot in it must leave. Off in the class; the
  // factory turns it on by default (SolverOptions::pocket_exit).
  void set_pocket_exit(bool on) override { pocket_exit_ = on; }

  const Config& current() const override { return current_; }
  const Config& goals() const override { return goals_; }
  bool at_goal() const override { return passes_goal_test(test_, current_, goals_); }
  uint64_t expansions() const override { return steps_planned_; }
  size_t explored() const override { return 0; }
  std::string name() const override { return "pibt-rot"; }

  // A robot asked to vacate its cell tries the cell behind it (a half turn: 3 steps to get
  // out) only after the others. Off in the class (plain PIBT ranking); the lifelong runner
  // turns it on by default (--no-rot-back-last): +4 to +7 % errands/step on MR23-I-04 / 03 /
  // 05 / 07 and +6 % tasks/step on WAREHOUSE, but -7 % on I-08 and -3 / -9 % on LoRR 2024
  // RANDOM-04 / 05 (docs/rotation_lorr.md).
  void set_back_last(bool on) override { back_last_ = on; }
  void set_headings(const std::vector<int>& headings) override;

  // Guidance (guidance.hpp): PIBT ranks a candidate by its action's cost + the guided
  // distance from there (a quarter turn turn_cost, forward forward_cost(v, o); waiting costs
  // the cheapest action). Drops the distance tables and takes the goals' anew; priorities
  // restart from the guided distances.
  void set_guidance(Guidance gd) override;
  // Distance queries past `d` answer lower bounds (RotationDist::set_deadline).
  void set_deadline(RotationDist::Deadline d) override { dist_.set_deadline(d); }

  const std::vector<int>& headings() const override { return heading_; }
  // The planned step's action per robot, one of "FRCW" (valid after search()).
  const std::string& actions() const override { return action_; }
  uint16_t h(int agent) const override { return dist_.get(goal_table_[agent], current_[agent], heading_[agent]); }
  const RotationDist& dist() const override { return dist_; }
  RotationDist& dist() { return dist_; }
  RotationDist::Table* goal_table(int agent) const { return goal_table_[agent]; }
  // Lifelong runs: goals known to come (RotationDist::prefetch), grown in spare time.
  void prefetch(const std::vector<Vertex>& goals) override { dist_.prefetch(goals); }
  bool precompute(std::chrono::steady_clock::time_point deadline) override { return dist_.precompute(deadline); }
  size_t pending() const override { return dist_.pending(); }

  // Rollouts (Wppl): the state that commit() changes, to step the planner ahead and back.
  struct Snapshot {
    Config current;
    std::vector<int> heading;
    std::vector<double> prio;
    std::vector<int32_t> order;
    std::vector<Vertex> target;
    std::vector<int> blocked;
    Rng rng;
    uint64_t steps_planned = 0;
  };
  Snapshot snapshot() const;
  void restore(const Snapshot& s);
  // Commits `actions` (one of "FRCW" per robot; a valid joint step, the caller's check)
  // instead of the planned ones; a robot whose action differs drops the cell it turned to.
  void commit_actions(const std::string& actions);

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
  std::vector<float> hint_;  // the task layer's priority hints
  std::vector<int32_t> order_;
  std::vector<int32_t> occ_now_, occ_next_;  // cell -> agent or -1
  std::vector<Vertex> decided_;               // per agent: its cell for this step's PIBT (-1: undecided)
  std::vector<Vertex> target_;                // per agent: the cell it turns toward (-1: none)
  std::vector<char> memo_;
  std::vector<int> blocked_;                  // per agent: steps waited facing its target
  std::string action_;
  bool planned_ = false;
  bool back_last_ = false;
  uint32_t wait_cost_ = 1;
  std::vector<Vertex> pocket_;  // vertex -> its dead-end pocket, or -1 (set_pockets)
  PocketExit exit_;             // the pocket exit rule's labels and depths (set_pockets)
  bool pocket_exit_ = false;
  uint32_t pocket_cost_ = 0;    // in the distances' costs
  uint64_t steps_planned_ = 0;
};

}  // namespace planner
