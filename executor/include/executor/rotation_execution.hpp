#pragma once
// RotationExecution: runs a cell-space plan on robots with a heading (LoRR's MAPF_T); an
// Execution (execution.hpp). Geometry: planner/heading.hpp.
//
// Why plan in cell space and adapt (and not plan over (cell, heading) states): RT-LaCAM's
// reroot reverses one tree edge, so the old root must be reachable in one step from the
// new one. Cell moves on the undirected 4-connected graph are reversible; MAPF_T moves are
// not (forward has no backward inverse: undoing it takes two turns, a forward and two
// turns), and conflicts are on cells, not on states, which PIBT's occupancy does not see.
// So the planner keeps its graph and its guarantees, and this adapter turns each committed
// cell move into LoRR actions.
//
// Execution order (an action dependency graph, Hoenig et al. 2019, on the committed plan):
// configurations C_0, C_1, ..., C_K arrive from the planner (push). Robot i is at plan
// index p_i and stands on C_{p_i}[i]. A plan wait costs no step (p_i advances over it). To
// make its next move u -> v, i turns toward v (one step per quarter turn, staying on u),
// then moves forward once every earlier visit of v in the plan has ended: each cell keeps
// its visits (robot, first plan index) in plan order, and i may enter v when its visit is
// the first, or the second behind a robot that leaves v in this very step (following, which
// LoRR allows; a cycle of followers rotates together). Robots thus visit every cell in the
// plan's order, so executed steps have no vertex conflicts, and no swaps either: two
// robots swapping u and v would each have to wait for the other's earlier visit.
// Executing a prefix of a valid plan this way never deadlocks (every dependency points to
// an earlier plan index), so every robot reaches C_K.
//
// The planner may run at most `window` configurations ahead of the slowest robot
// (can_accept). Goals must follow the robots' real cells (errands complete on arrival),
// so a larger window pipelines turns better but reacts later to completions.
#include <string>
#include <vector>

#include "executor/execution.hpp"
#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace executor {

class RotationExecution : public Execution {
 public:
  // All robots face east (heading 0), as in LoRR. `window` >= 1.
  RotationExecution(const planner::Graph& g, const planner::Config& starts, int window);

  bool can_accept() const override { return frontier_ - min_progress_ < window_; }
  // The planner's next committed configuration: a valid cell-space step from frontier().
  void push(const planner::Config& next) override;
  // One timestep; actions() then holds one LoRR letter per robot: F, R, C or W.
  void step() override;
  bool idle() const override { return min_progress_ == frontier_; }

  const planner::Config& positions() const override { return pos_; }
  const std::vector<int>& headings() const override { return heading_; }
  const std::string& actions() const override { return actions_; }
  const planner::Config& frontier_config() const { return plan_.back(); }
  long frontier() const { return frontier_; }      // K: index of the last pushed configuration
  long progress(int i) const { return progress_[i]; }

 private:
  struct Visit {
    int agent;
    long start;  // plan index at which the robot enters the cell
  };
  const planner::Vertex& at(long k, int i) const { return plan_[static_cast<size_t>(k - base_)][i]; }
  bool moves(int i);  // may robot i go forward now (memoised per step)

  const planner::Graph& g_;
  int window_;
  std::vector<planner::Config> plan_;  // C_base .. C_K (trimmed below the slowest robot)
  long base_ = 0, frontier_ = 0, min_progress_ = 0;
  planner::Config pos_;
  std::vector<int> heading_;
  std::vector<long> progress_;
  std::vector<std::vector<Visit>> visits_;  // per cell, in plan order; front = current or next visitor
  std::vector<char> want_, memo_;           // per step
  std::vector<planner::Vertex> target_;
  std::string actions_;
};

// A whole cell-space plan C_0..C_T run under MAPF_T (one-shot MAPF: rtlacam-bench
// --action-model rotation): timesteps until every robot stands on C_T, sum over robots of
// the step of its last action, and the first executed step that fails the validator.
struct RotationRun {
  long makespan = 0, soc = 0, turns = 0;
  std::string error;  // "" when every step is valid
};
RotationRun run_with_rotation(const planner::Graph& g, const std::vector<planner::Config>& plan);

}  // namespace executor
