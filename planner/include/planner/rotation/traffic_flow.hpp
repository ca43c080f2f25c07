#pragma once
// TrafficFlow: congestion-aware guide paths computed online, for the rotation action model
// (after Chen, Harabor, Li, Stuckey, "Traffic Flow Optimisation for Lifelong Multi-Agent
// Path Finding", AAAI 2024; written anew from the paper's description).
//
// Why: at 49-73 % density (MR23-I-05/07) every robot following its own shortest (guided)
// path sends flows head-on into each other, and PIBT-style planners stall in the jams. The
// paper's remedy: each robot plans a *guide path* whose edge costs grow with the traffic
// of the others' guide paths, and the one-step planner follows that guide.
//
// Model. Every robot with a guide path contributes its forward moves (v facing o -> u) to
// two flow counts, kept incrementally (add / remove a path):
//   flow(v, o)  robots whose guide path moves forward from v facing o (a directed edge);
//   load(u)     guide-path moves entering u (vertex load).
// A forward move from v facing o into u then costs, for the robot planning now,
//   kScale * forward_cost(v, o)                      (the guidance graph's cost, guidance.hpp,
//                                                     plus u's extra move cost: rotation_dist.hpp)
//   + round(kScale * contraflow * flow(u, o + 2))    (robots planned to cross it the other way)
//   + round(kScale * vertex * load(u))               (robots planned through u)
// and a quarter turn kScale * turn_cost. These are the marginal increases of the paper's
// objective terms (pairs of opposite flows on an edge; flows sharing a vertex), weighted.
// Costs are integers (kScale = 16ths of a guidance unit) so that distances stay exact.
//
// Per robot: a full backward Dijkstra from its goal cell's four states over (cell,
// heading) under those costs, frozen when computed (its own path is removed first, so it
// does not repel itself): `h(agent, v, o)`, the congestion-aware distance the planner ranks
// its moves by (the per-robot table variant of the paper's heuristic: from wherever a
// robot is pushed it follows the cheapest congested route, it does not return to the old
// path). Its guide path is traced from the robot's state down that table and added to the
// flows; advance() removes each move the robot actually makes, so only the part still
// ahead loads the map.
//
// Cost: a table is 4 x cells uint32 (13 KB on random-32-32-20) and a Dijkstra over all
// states (~0.1-0.3 ms there); robots x 4 x cells entries in all. The owner bounds it
// (Options::max_entries) and keeps the feature off where it would not fit (LoRR 2024
// WAREHOUSE: 10,000 robots x 150 k states).
#include <cstdint>
#include <vector>

#include "planner/rotation/rotation_dist.hpp"

namespace planner {

struct TrafficFlowOptions {
  bool on = false;
  // Weights and refresh chosen on MR23-I-05 / I-07 seed 0 (docs/rotation_lorr.md "Traffic flow").
  double contraflow = 1.0;  // weight of each robot planned across the edge the other way
  double vertex = 0.1;      // weight of each guide-path move into the cell
  // Guide paths re-planned beyond goal changes (round robin; 0: only on a goal change): Epibt
  // re-plans this many each time its queue of new goals is done before a step is planned
  // (in search(), and in a pre-search precompute() that had new goals: up to twice per step).
  int refresh = 4;
  double share = 0.5;          // of a step's budget for guide-path work; the rest waits for the next step
  size_t max_entries = 1u << 26;  // robots x 4 x cells above this: off (256 MB of tables)
};

class TrafficFlow {
 public:
  using Options = TrafficFlowOptions;
  static constexpr uint32_t kScale = 16;
  static constexpr uint32_t kInf = 0xFFFFFFFFu;

  // Whether the guide tables of `agents` robots on `cells` cells stay within opt.max_entries
  // (owners keep the feature off otherwise).
  static bool fits(size_t agents, int cells, const Options& opt) { return agents * 4 * static_cast<size_t>(cells) <= opt.max_entries; }

  // `dist` gives the map (ahead) and the guidance costs; it must outlive this object.
  TrafficFlow(const RotationDist& dist, size_t agents, Options opt);

  // Replans `agent`'s guide: removes its path from the flows, computes its table to `goal`
  // under the current congestion costs, traces its guide path from (v, o) and adds it.
  void plan(int agent, Vertex v, int o, Vertex goal);
  // Removes `agent`'s path and table (e.g. its goal changed); has() is false until plan().
  void drop(int agent);
  bool has(int agent) const { return !table_[static_cast<size_t>(agent)].empty(); }
  // Congestion-aware cost-to-go (kScale units) from (v, o); kInf if the goal is unreachable.
  uint32_t h(int agent, Vertex v, int o) const { return table_[static_cast<size_t>(agent)][static_cast<size_t>(v) * 4 + static_cast<size_t>(o)]; }
  // The robot made a forward move from v facing o: if it is the next move of its guide
  // path, that move leaves the flows.
  void advance(int agent, Vertex v, int o);

  // The current cost of a forward move from v facing o (kInf: none) and of a quarter turn.
  uint32_t forward(Vertex v, int o) const;
  uint32_t turn() const { return kScale * dist_.turn_cost(); }

  // The guide path still ahead: its forward moves as states v * 4 + o, in order.
  std::vector<int32_t> path(int agent) const;
  uint32_t flow(Vertex v, int o) const { return flow_[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)]; }
  uint32_t load(Vertex v) const { return load_[static_cast<size_t>(v)]; }
  const Options& options() const { return opt_; }
  uint64_t plans() const { return plans_; }

 private:
  void add_path(int agent);
  void remove_path(int agent);

  const RotationDist& dist_;
  Options opt_;
  std::vector<std::vector<uint32_t>> table_;  // per agent: h over states v * 4 + o
  std::vector<std::vector<int32_t>> path_;    // per agent: forward moves v * 4 + o
  std::vector<size_t> head_;                  // per agent: moves before it are done
  std::vector<uint32_t> flow_;                // v * 4 + o
  std::vector<uint32_t> load_;                // v
  std::vector<std::pair<uint32_t, int32_t>> heap_;
  uint64_t plans_ = 0;
};

}  // namespace planner
