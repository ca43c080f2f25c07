#pragma once
// Immobile agents (RealtimePlanner::set_immobile): an agent that cannot move for a while --
// an AGV stuck in an aisle -- is a temporary obstacle. The planner keeps it where it is:
//   - PIBT never moves it and never pushes it: its only candidate is staying, so a
//     higher-priority agent asking it to make room fails and takes its next candidate, and
//     no swap pulls it (pibt.hpp); PIBT ranks the others' moves by distances AROUND the
//     immobile agents (DetourTable below) -- with plain distances an agent whose shortest
//     path runs through one would press against it and LaCAM would need many expansions
//     to find the detour;
//   - LaCAM's constraints for it have the one child "stay" (lacam.cpp grow_lowlevel), so
//     every constraint is one PIBT can honour, and LNS refinement (which replans agents by
//     A*, blind to the mask) is off while one is immobile;
//   - the goal test: "all agents on their goals" cannot pass while an immobile agent is off
//     its goal, and LaCAM would explore every reachable configuration before giving up.
//     Instead the search aims at the relaxed goal below (everybody who can reach its goal
//     around the obstacle is on it): the others route on. If even that is unreachable the
//     search ends with its Open list empty -- bounded by the configurations reachable with
//     the obstacle in place, like any LaCAM search -- and the planner waits (next() is the
//     current configuration); exhausted() stays false: the immobility is temporary.
// Setting or clearing the flag restarts the search at the current configuration (a tree
// built with other constraints is dropped). Clearing it restores the real goal test and so
// RT-LaCAM's completeness from there on.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"
#include "planner/search_types.hpp"

namespace planner {

// true if some agent is marked.
bool any_immobile(const std::vector<uint8_t>& immobile);
// Throws std::invalid_argument "set_immobile: agent 7 out of range (0..3)" unless 0 <= agent < n.
void check_immobile_agent(int agent, size_t n);

// The goal test while agents are immobile: every mobile agent whose goal lies in its own
// connected component of the graph minus the immobile agents' vertices is on its goal;
// the others (cut off, or their goal taken by an immobile agent) may end anywhere.
// `test` non-empty (a caller's own test, e.g. lifelong) is returned unchanged.
GoalTest relaxed_goal_test(const Graph& g, const Config& current, const Config& goals,
                           const std::vector<uint8_t>& immobile, GoalTest test = {});

// Distances to a goal on the graph without some blocked vertices (the immobile agents'):
// one full BFS per goal vertex, on first use, cached until the blocked set changes.
// DistTable::kInf where the goal cannot be reached (and on the blocked vertices).
class DetourTable {
 public:
  explicit DetourTable(const Graph& g) : g_(g) {}
  // Sets the blocked vertices (sorted or not); drops the cache when they change.
  void set_blocked(std::vector<Vertex> blocked);
  bool active() const { return !blocked_.empty(); }
  int32_t get(Vertex goal, Vertex v);

 private:
  const Graph& g_;
  std::vector<Vertex> blocked_;
  std::unordered_map<Vertex, std::vector<int32_t>> tables_;
};

}  // namespace planner
