#pragma once
// The physical bound of a run (issue 21): every AGV alone on the path it was planned, with
// its vType's kinematics. It separates what physics forces from what the executor and the
// congestion cost: makespan / bound (one-shot), throughput / bound (lifelong).
//
// An AGV drives each stretch between two rests as one trapezoid (accel up, max_speed,
// decel down to rest on the last cell); it rests where its path reverses (a turn in place:
// one SUMO step at rest, as the Driver needs) and at the path's end. Moves are measured
// between the cells' centres. Waits are dropped: alone, nobody waits. For lockstep (scheme
// S: one cell per tick, stops in one step) the bound is the longest path in moves, plus,
// for the rotation solvers, the quarter turns each move needs from the AGV's heading (a
// turn is a plan step too: count_turns). Under physics with headings (adg with a rotation
// solver) a move in a new direction ends the stretch: the AGV comes to rest, rests one SUMO
// step (the Driver turns only an AGV SUMO reports at rest) and turns on its cell, turn_s per
// quarter turn.
#include <vector>

#include "gridify/cell_map.hpp"
#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace controller {

struct Kinematics {
  double accel = 0.5, decel = 1.0, max_speed = 1.0;
  double dt = 0.125;  // SUMO step: a turn in place rests one step
};

// Seconds from rest to rest over `metres`.
double rest_to_rest_s(double metres, const Kinematics& k);

// Per agent, seconds to drive its path in `plan` (consecutive configurations) alone.
std::vector<double> alone_s(const gridify::CellMap& map, const std::vector<planner::Config>& plan, const Kinematics& k);

// Per agent, the moves of its path in `plan` (one tick each in lockstep).
std::vector<double> alone_moves(const std::vector<planner::Config>& plan);

// Either of the two, fed one configuration at a time (a lifelong run does not keep its
// whole plan: controller/executed_plan.hpp). map == nullptr: moves (alone_moves).
class AloneBound {
 public:
  AloneBound(const gridify::CellMap* map, const Kinematics& k) : map_(map), k_(k) {}
  // AGVs with headings on the lattice `g`, facing `start_headings` (planner/heading.hpp);
  // each move first turns toward its direction: one step per quarter turn (moves mode), or
  // rest + turn_s per quarter turn (physics).
  void count_turns(const planner::Graph& g, std::vector<int> start_headings, double turn_s = 0);
  void add(const planner::Config& c);
  std::vector<double> result() const;

 private:
  const gridify::CellMap* map_;
  Kinematics k_;
  planner::Config last_, before_;   // per agent: its path's last cell and the one before
  std::vector<double> stretch_, t_;  // metres since the last rest; seconds (or moves) so far
  const planner::Graph* turns_on_ = nullptr;
  std::vector<int> heading_;  // count_turns: each AGV's heading after its last move
  double turn_s_ = 0;
};

}  // namespace controller
