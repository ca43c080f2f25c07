#pragma once
// Wppl (solver `wppl`): windowed LNS refinement over rotation-model windows, after WPPL
// (Windowed Parallel PIBT-LNS; Jiang, Zhang, Veerapaneni, Li, "Scaling Lifelong Multi-Agent
// Path Finding to More Realistic Settings", SoCS 2024, the LoRR 2023 winner). Written anew
// from the paper and a reading of its code (no code copied); single-threaded here.
//
// Each step:
//  1. An initial plan of every robot's (cell, heading) over a window of W steps: RotationPibt
//     (the `pibt-rot` step) rolled forward W steps from the current state and put back
//     (RotationPibt::snapshot / restore; goals stay fixed inside the window). With
//     `reuse_tail`, the last step's refined plan shifted by the executed step, its last
//     step made by one PIBT step from its end states (as WPPL extends its previous plan;
//     conflict-free: PIBT's step is), competes with it: the one of lower objective starts
//     the LNS, so LNS work carries over between steps. (A wait as the last step instead
//     deadlocked dense maps: MR23-I-07 0.20 errands/step, docs/rotation_lorr.md.)
//  2. LNS (MAPF-LNS, Li et al. IJCAI 2021) until the budget ends: a neighbourhood of up to
//     `neighbourhood` robots (a delayed robot, picked at random, and the robots whose
//     windowed paths stand, at any t, on the cells of its ideal route, the descent of its h
//     over W steps: the robots in its way, `neighbourhood` of them at most: 8 by default, best at the
//     low densities where wppl is the solver to use), its paths
//     removed and replanned one by one in random order by space-time A* over (cell,
//     heading, t) against the others' (st_astar_rot.hpp); kept if the sum of their windowed
//     costs drops or stays equal (`accept_ties`: sideways moves), else put back. Objective:
//     the sum over robots of the windowed cost (the first time on the goal, else W + h(end
//     state) from RotationDist: the cost to goal).
//  3. The first step of the refined plan is the step: one F / R / C / W per robot, free of
//     vertex and swap conflicts on cells (turns keep the cell, following allowed), as
//     LoRR's ActionModelWithRotate checks it. With no LNS iteration it is pibt-rot's step.
// The PIBT state (priorities, cells robots turn toward) follows the executed step
// (RotationPibt::commit_actions).
//
// Budget: the wall-clock limit of search() bounds the LNS (the rollout is always made);
// Budget::expansions (and WpplOptions::max_iters) count LNS iterations, for deterministic
// runs. expansions() counts steps + LNS iterations.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "planner/rng.hpp"
#include "planner/rotation/rotation_pibt.hpp"
#include "planner/rotation/rotation_planner.hpp"
#include "planner/rotation/st_astar_rot.hpp"

namespace planner {

struct WpplOptions {
  int window = 20;         // W: steps planned ahead (WPPL: 15; 20 wins here, docs/rotation_lorr.md s18)
  int neighbourhood = 8;  // robots replanned per LNS iteration at most (64 before s17; docs/rotation_lorr.md "Where it stands (s17)")
  uint64_t max_iters = 0;  // LNS iterations per step at most (0: the budget decides)
  bool reuse_tail = true;  // start from the last plan's tail when it is better than the rollout
  bool pareto = false;     // accept a neighbourhood's new paths only if none costs more
  bool accept_ties = true; // accept new paths of equal windowed cost too (sideways moves)
};

class Wppl : public RotationPlanner {
 public:
  Wppl(const Graph& g, const Config& starts, const Config& goals, uint64_t seed = 0, GoalTest test = {},
       int heading = 0, WpplOptions opt = {});

  Status search(const Budget& b) override;
  const Config& next() override;
  void commit() override;
  void set_goals(const Config& goals, GoalTest test = {}) override;
  void set_max_dist_tables(size_t n) override { pibt_.set_max_dist_tables(n); }

  const Config& current() const override { return pibt_.current(); }
  const Config& goals() const override { return pibt_.goals(); }
  bool at_goal() const override { return pibt_.at_goal(); }
  uint64_t expansions() const override { return steps_ + iters_; }
  size_t explored() const override { return 0; }
  std::string name() const override { return "wppl"; }

  const std::vector<int>& headings() const override { return pibt_.headings(); }
  const std::string& actions() const override { return action_; }
  uint16_t h(int agent) const override { return pibt_.h(agent); }
  const RotationDist& dist() const override { return pibt_.dist(); }
  void prefetch(const std::vector<Vertex>& goals) override { pibt_.prefetch(goals); }
  bool precompute(std::chrono::steady_clock::time_point deadline) override { return pibt_.precompute(deadline); }
  size_t pending() const override { return pibt_.pending(); }
  void set_back_last(bool on) override { pibt_.set_back_last(on); }
  void set_pocket_exit(bool on) override { pibt_.set_pocket_exit(on); }
  void set_headings(const std::vector<int>& headings) override;
  // Guidance reaches the rollout's PIBT and h(end state) of the objective; the windowed part
  // still counts steps (a plan that reaches its goal at t costs t < W + any h).
  void set_guidance(Guidance gd) override { pibt_.set_guidance(std::move(gd)); }
  void set_deadline(RotationDist::Deadline d) override { pibt_.set_deadline(d); }
  // Foreign pockets (tasks.urgency.pocket_cost): the rollout's PIBT ranks a move into a
  // dead-end pocket other than the robot's goal's `cost` moves worse (RotationPibt::set_pockets),
  // and a windowed path that enters one from outside costs `cost` moves more in the LNS
  // objective, so the LNS does not undo it for a shorter path (space-time A* plans without
  // it; its paths into a foreign stub lose). Empty or 0: off (unchanged decisions).
  void set_pockets(std::vector<Vertex> pocket, float cost) override;

  void set_options(const WpplOptions& opt);  // between steps
  const WpplOptions& options() const { return opt_; }

  // The current window (after search()): per robot its states at t = 0..W.
  const std::vector<RotPath>& plan() const { return plan_; }
  int64_t objective() const { return objective_; }                  // of plan()
  int64_t initial_objective() const { return initial_objective_; }  // of this step's initial plan
  uint64_t lns_iterations() const { return iters_; }                // totals over all steps
  uint64_t lns_accepted() const { return accepted_; }
  uint64_t lns_sideways() const { return sideways_; }             // accepted at equal cost
  uint64_t tail_starts() const { return tail_starts_; }             // steps that started from the last plan's tail

 private:
  void initial_plan();
  bool lns_iteration(Clock::time_point deadline);
  void neighbourhood(std::vector<int>& out);
  int64_t cost(int i) const { return windowed_cost(pibt_.dist(), pibt_.goal_table(i), goals()[i], plan_[i]) + pocket_penalty(i, plan_[i]); }
  int64_t pocket_penalty(int i, const RotPath& p) const;  // pocket_cost_ if p enters a foreign pocket, else 0

  const Graph& g_;
  RotationPibt pibt_;
  WpplOptions opt_;
  Rng rng_;
  StAstarRot astar_;
  RotReservations res_;
  std::vector<RotPath> plan_, tail_;
  std::vector<Vertex> pocket_;  // vertex -> its dead-end pocket, or -1 (set_pockets)
  int64_t pocket_cost_ = 0;     // in the units of h (guided: min_forward() per move)
  std::vector<int64_t> cost_;
  std::vector<int> in_nb_;  // per robot: stamp of the neighbourhood it is in
  std::vector<uint16_t> h0_;  // per robot: h of its state now (this step's)
  std::vector<int> delayed_, cand_, nb_;  // neighbourhood() buffers
  std::vector<RotPath> paths_;              // lns_iteration() buffers
  std::vector<int64_t> costs_;
  int nb_stamp_ = 0;
  Config next_;
  std::string action_;
  bool planned_ = false, tail_valid_ = false;
  int64_t objective_ = 0, initial_objective_ = 0;
  uint64_t steps_ = 0, iters_ = 0, accepted_ = 0, sideways_ = 0, tail_starts_ = 0, iters_step_ = 0;
};

}  // namespace planner
