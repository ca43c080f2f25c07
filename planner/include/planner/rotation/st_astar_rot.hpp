#pragma once
// Space-time A* over (cell, heading, t) for the rotation action model (LoRR's MAPF_T), the
// low level of Wppl's LNS (wppl.hpp): one robot's best path through a window of W steps
// against the windowed paths of the others, kept in a reservation table (MAPF-LNS, Li et
// al. IJCAI 2021; WPPL, Jiang et al. SoCS 2024, plans the same way in its rotation model).
//
// Moves per step: F into the cell ahead, R / C turn in place, W wait; a turn keeps the
// cell. Conflicts are on cells, as LoRR checks them: a vertex conflict (two robots on one
// cell at t + 1) and a swap (two robots exchange cells between t and t + 1). Following (a
// robot enters the cell another leaves in the same step) and cycles are allowed.
//
// Objective of a windowed path (the windowed cost to goal): the first t in 0..W at which
// the robot stands on its goal cell (any heading), else W + h(state at W) from its
// RotationDist table. A* on f = g + h with g = t until the goal is reached (then the path
// only has to stay conflict-free to W, at no cost): exact when h is (h is consistent for
// unit steps, and W + h(end) >= t + h(now) as h drops by at most one per step). The open
// list is a bucket queue on f, last in first out within a bucket (ties go to the states
// generated last, mostly the deeper ones: dives). Reached and not-reached states are
// distinct (a state after the goal was reached costs nothing more).
#include <chrono>
#include <cstdint>
#include <vector>

#include "planner/rotation/rotation_dist.hpp"

namespace planner {

struct RotState {
  Vertex v;
  int o;  // heading: 0 east, 1 south, 2 west, 3 north
  bool operator==(const RotState& s) const { return v == s.v && o == s.o; }
};
using RotPath = std::vector<RotState>;  // states at t = 0..W

// The windowed paths' cells per time step: cell x t -> robot or -1.
class RotReservations {
 public:
  void reset(int cells, int window);
  int window() const { return window_; }
  int at(Vertex v, int t) const { return occ_[static_cast<size_t>(t) * cells_ + static_cast<size_t>(v)]; }
  void add(int agent, const RotPath& p);
  void remove(int agent, const RotPath& p);
  // May a robot be on v at t (t >= 1)?
  bool vertex_free(Vertex v, int t) const { return at(v, t) < 0; }
  // May a robot move u -> v between t and t + 1 (v free at t + 1, no swap with v's robot)?
  bool move_free(Vertex u, Vertex v, int t) const
  {
    if (!vertex_free(v, t + 1)) return false;
    const int b = at(v, t);
    return b < 0 || at(u, t + 1) != b;
  }

 private:
  size_t cells_ = 0;
  int window_ = 0;
  std::vector<int32_t> occ_;
};

// The windowed objective of a path (see above).
int64_t windowed_cost(const RotationDist& dist, RotationDist::Table* t, Vertex goal, const RotPath& p);

class StAstarRot {
 public:
  explicit StAstarRot(const RotationDist& dist) : dist_(dist) {}

  // The best path from `s` over `res.window()` steps; its windowed cost, or -1 when every
  // path conflicts (or the deadline passed: checked every 1024 expansions).
  int64_t plan(RotState s, Vertex goal, RotationDist::Table* t, const RotReservations& res, RotPath& out,
               std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());
  uint64_t expanded() const { return expanded_; }  // total over all calls

 private:
  struct Node {
    uint32_t seen = 0;    // stamp of the call that generated it
    uint32_t closed = 0;  // stamp of the call that expanded it
    int32_t g = 0;        // best cost so far (valid where seen)
    int32_t parent = -1;
  };
  const RotationDist& dist_;
  std::vector<Node> node_;                     // per key (t, cell, heading, reached)
  std::vector<std::vector<int32_t>> bucket_;   // open keys per f (LIFO: deeper states first)
  uint32_t stamp_ = 0;
  uint64_t expanded_ = 0;
};

}  // namespace planner
