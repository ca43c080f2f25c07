#pragma once
// Reachability: which cells can still reach an errand cell while closures (controller/
// rules.hpp) take arcs out of the net (issue 24: "a closure that isolates a goal:
// reassign"). The task layer asks it before it hands out a task and while an agent heads
// for its errand; an errand it says no to goes back to the pool (task_pool.hpp).
//
// One backward breadth-first search per errand cell asked about (along in-neighbours, so
// one-way aisles count right), kept until the graph changes: a pool asks about
// agents x free tasks pairs but only about a few station cells, so this is O(cells) per
// station, not per pair.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "planner/graph.hpp"

namespace tasks {

class Reachability {
 public:
  // `g` must outlive this (the controller's graph without the arcs into closed cells).
  explicit Reachability(const planner::Graph& g) : g_(g) {}
  bool reaches(planner::Vertex from, planner::Vertex to) const;

 private:
  const planner::Graph& g_;
  mutable std::unordered_map<planner::Vertex, std::vector<uint8_t>> to_;  // target -> cells that reach it
};

}  // namespace tasks
