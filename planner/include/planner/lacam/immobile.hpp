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
#include <memory>
#include <unordered_map>
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_cache.hpp"
#include "planner/graph.hpp"
#include "planner/search_types.hpp"

namespace planner {

class DistTable;

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

// Distances to a goal on the graph without some blocked vertices (the immobile agents'),
// DistTable::kInf where the goal cannot be reached (and on the blocked vertices).
// They differ from the plain distances d (`plain`'s tables) only in the blocked vertices'
// shadow: the vertices all of whose shortest paths run through one. So per goal, on first
// use, only the shadow is searched -- from each blocked vertex b outwards, a vertex at d+1
// is in it when every move down to d lands on a blocked or shadowed vertex -- and its
// distances are repaired from its exits (a Dijkstra over the shadow); everything else reads
// d. A stuck AGV in an aisle shadows the aisle behind it: tens of vertices per goal where a
// BFS per goal over the whole graph was 75 ms for 1000 agents (huge warehouse), in the
// step that starts a stuck replan. And a goal's shadow is searched only once a query meets
// (With move costs, graph.hpp, every +1 here is the cost of the vertex moved onto.)
// a vertex with a shortest path through a blocked vertex b (d(v) == d(b) + |v -> b|, from
// one BFS per blocked vertex): most agents' paths pass no stuck AGV and cost nothing. Exact for a query at v for the blocked vertices nearer
// the goal than v (the only ones a shortest path from v can meet; d's BFS has found them
// when it found v); a detour that would pass a farther one is a lower bound. Tables are
// cached until the blocked set changes, and redone for a goal when its BFS has found
// another blocked vertex since. Past the deadline of `plain`'s cache no shadow is searched
// (d, a lower bound, instead; the next query before a deadline searches it), so the
// searches of a new blocked set -- hundreds of vertices per goal in a warehouse whose
// aisles funnel many goals' paths -- spread over the steps that query them.
class DetourTable {
 public:
  // `plain`: the distances without obstacles (null: tables of its own).
  explicit DetourTable(const Graph& g, DistTable* plain = nullptr);
  ~DetourTable();
  // Sets the blocked vertices (sorted or not); drops the cache when they change.
  void set_blocked(std::vector<Vertex> blocked);
  bool active() const { return !blocked_.empty(); }
  int32_t get(Vertex goal, Vertex v);
  // The same with the goal's plain table at hand (an agent's: DistTable::table()).
  int32_t get(Vertex goal, Vertex v, DistCache::Table* plain);
  // Work so far: vertices the shadow searches have looked at (a BFS per goal: |V| each).
  uint64_t searched() const { return searched_; }

 private:
  struct Shadow {
    Vertex goal = -1;
    size_t found = 0;                          // blocked vertices it accounts for
    std::unordered_map<Vertex, int32_t> dist;  // the shadow's repaired distances
  };
  bool blocked(Vertex v) const;
  void build(Shadow& s, size_t found, DistCache::Table* plain);

  const Graph& g_;
  std::vector<std::vector<int32_t>> to_blocked_;  // per blocked vertex: |v -> b| (BFS over in-arcs)
  std::vector<uint32_t> stamp_;                   // vertex -> shadow mark of the build in progress
  uint32_t epoch_ = 0;
  uint64_t searched_ = 0;
  std::unique_ptr<DistTable> own_;  // without `plain`
  DistTable* plain_;
  std::vector<Vertex> blocked_;
  std::vector<Shadow> shadows_;
  std::vector<int32_t> shadow_of_;  // goal vertex -> its entry in shadows_, -1: none
};

}  // namespace planner
