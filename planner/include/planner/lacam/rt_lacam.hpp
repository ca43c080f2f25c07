#pragma once
// RtLacam: Real-Time LaCAM (Liang, Veerapaneni, Harabor, Li, Likhachev; SoCS 2025).
//
// One LaCAM search is built up across planning iterations. search(budget) continues the
// DFS where the last call stopped; next() walks parent pointers from the top of the DFS
// stack back to the root -- which is always the current configuration -- and returns the
// root's child on that path (or the root: wait). commit() moves the agents there and
// reroots the tree by reversing that one edge. The explored table and every constraint
// survive, so revisits still force new successors and the search is the very same one
// full-horizon LaCAM runs: same expansions, same explored set, hence complete, with no
// deadlock or livelock. Once the goal is found the agents follow the tree path to it: with
// LacamOptions::refine off (the paper) without further search; with it on (RT-LaCAM*) the
// search goes on as LaCAM* with every iteration's budget, and next() follows the best path
// to the goal known now, re-read each iteration, so the path improves while the agents
// move. Rerooting re-bases g at the new root (lacam.hpp): the executed prefix is sunk cost.
//
// Directed graphs (one-way arcs). Reversing the executed edge needs the reverse move, which
// a one-way arc lacks. Rule: before a goal node is known, next() returns only moves that
// can be undone (every agent that moves has the reverse arc); a step toward the top of the
// DFS stack that uses a one-way arc is replaced by waiting at the root while the search
// goes on. Once a goal node is known the agents follow its tree path, one-way arcs
// included; a reroot over a one-way move then ends LaCAM* refinement (lacam.hpp), since the
// old root is no longer reachable and no rewrite may route through it.
// Guarantees:
//  - undirected graphs: complete, as above (unchanged);
//  - any finite directed graph, with a start from which the goal configuration is
//    reachable: complete. Before the goal node exists every executed transition is
//    reversible, so each current configuration reaches exactly the configurations the
//    start reaches, every tree edge (original or reversed) is a legal move, and the search
//    is the same single LaCAM search from the start, which finds the goal node; the agents
//    then follow its tree path. If no goal configuration is reachable the search ends with
//    NoSolution (exhausted()), as LaCAM does; an agent whose goal is unreachable from its
//    start along the arcs is refused at construction / set_goals with
//    std::invalid_argument. Strong connectivity is not required for this guarantee, but
//    lifelong runs (a new goal after each errand) need every goal reachable from wherever
//    an agent stands: gridify keeps the largest strongly connected component.
//  - the caveat: where most moves are one-way (a warehouse of one-way aisles) the agents
//    mostly wait until the search finds the goal, so RT-LaCAM acts like full-horizon LaCAM
//    run across iterations; it is never worse than LaCAM in iterations to a solution, but
//    the agents do not make progress while it searches.
//
// Lookahead (directed graphs). The first one-way move along the goal's path ends LaCAM*
// refinement, so a long first solution (LaCAM's DFS can run hundreds of steps deep) would be
// followed to its end: on warehouse-10-20-10-2-1 with one-way aisles, N = 400, 1 ms per
// iteration, makespan 1242 where full-horizon LaCAM* gets 618; in a lifelong SUMO run 16
// AGVs drove 1290 steps without an errand. So while the followed search is idle (refinement
// over) and its path is long, a second search (a fresh Lacam, same options, goals and goal
// test) starts from the path's configuration k steps on (k = a quarter of the path, 8..64)
// and gets every iteration's budget, which the idle search does not use. When the agents
// reach that configuration the lookahead replaces the followed search if its path to a goal
// is strictly shorter and, where both are priced (objective soc), no dearer in the standard
// SOC; else it is dropped. Either way a new one may start. Completeness is kept: the agents
// always follow a legal path to a goal node, each switch strictly shortens the steps left to
// it, and there are at most 8 switches per search (goals or restart): after the last one the
// followed search refines until its first one-way move and its path is then followed to the
// goal, as without lookahead. (Uncapped, a switched-to search that refined to a cheaper but
// longer path was switched away from again: a crowded one-way warehouse ran 3000 steps without
// reaching the goal.) Undirected graphs never start one (refinement never ends on a move
// there), nor does the paper's RT-LaCAM (refine off).
//
// commit() moves to the configuration next() last returned, even if search() ran in
// between (an executor may keep thinking while the agents move): that node was the root's
// tree child, hence a valid move; if LaCAM* re-parented it meanwhile, reroot() still makes
// it the root (the link to the old root stays).
#include <memory>
#include <vector>

#include "planner/lacam/immobile.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/realtime_planner.hpp"

namespace planner {

class RtLacam : public RealtimePlanner {
 public:
  RtLacam(const Graph& g, const Config& starts, const Config& goals, LacamOptions opt = {},
          ActionPreference* pref = nullptr, GoalTest test = {},
          std::shared_ptr<DistCache> cache = nullptr);


  Status search(const Budget& b) override;
  const Config& next() override;
  void commit() override;
  void set_goals(const Config& goals, GoalTest test = {}) override;
  void set_max_dist_tables(size_t n) override { dist_.set_max_tables(n); }
  void share_dist_cache(std::shared_ptr<DistCache> c) override { dist_.share(std::move(c)); }
  void set_immobile(int agent, bool immobile) override;
  void set_immobile(const std::vector<uint8_t>& immobile) override;  // one restart for all
  void set_priority_hint(std::vector<float> hint) override { hint_ = std::move(hint); }
  void set_pockets(std::vector<Vertex> pocket, float cost) override
  {
    pockets_ = pocket, pocket_cost_ = cost;
    lacam_->set_pockets(std::move(pocket), cost);
    if (ahead_) ahead_->set_pockets(pockets_, cost);
  }
  bool restart_at(const Config& at, const Config& goals, GoalTest test, const std::vector<uint8_t>& immobile) override;
  uint64_t restarts() const { return restarts_; }  // searches restarted at current() so far
  uint64_t lookaheads() const { return lookaheads_; }  // lookahead searches started (directed graphs)
  uint64_t switches() const { return switches_; }      // of those, taken over

  const Config& current() const override { return current_; }
  const Config& goals() const override { return lacam_->goals(); }
  bool at_goal() const override;
  // Never while an agent is immobile: the relaxed search may run dry, the immobility ends.
  bool exhausted() const override { return lacam_->status() == Status::NoSolution && !any_immobile(immobile_); }
  uint64_t expansions() const override
  {
    return retired_expansions_ + (lacam_->expansions() - main_base_) + (ahead_ ? ahead_->expansions() - ahead_base_ : 0);
  }
  double max_expansion_ms() const override { return lacam_->max_expansion_ms(); }  // Lacam::max_expansion_ms
  size_t explored() const override { return lacam_->explored(); }
  std::string name() const override { return "rtlacam"; }
  const Graph* graph() const override { return &g_; }

  const Lacam& lacam() const { return *lacam_; }  // for tests and statistics

 private:
  const HNode* planned();
  void restart(const Config& goals);  // a new search at current_ (priorities carried if kept)
  void look_ahead();                  // after a move on a directed graph (header)
  void start_ahead();                 // in search(): the lookahead chosen by look_ahead()
  void drop_ahead();

  // Lookahead distance in steps: a quarter of the followed path, within these.
  static constexpr int kAheadMin = 8, kAheadMax = 64;
  // Switches per search (goals, restart): a switched-to search refines, and refinement may
  // trade steps for cost, so "strictly shorter" alone could switch back and forth for ever.
  static constexpr int kMaxSwitches = 8;

  DistTable dist_;
  std::unique_ptr<Lacam> lacam_;         // the search the agents follow
  std::unique_ptr<Lacam> ahead_;         // directed graphs: a search from ahead_at_, or null
  std::unique_ptr<Lacam> spare_;         // a dropped search, kept for the next lookahead
  Config ahead_at_;                      // the followed path's configuration k steps on
  int ahead_k_ = 0, ahead_steps_ = 0;    // k, and the moves made since the lookahead began
  bool ahead_pending_ = false;           // chosen, not started yet
  int epoch_switches_ = 0;               // switches since the last restart
  uint64_t lookaheads_ = 0, switches_ = 0;
  // Expansions: of dropped lookaheads, and each search's count when it began its present use
  // (a reused Lacam counts over all its resets).
  uint64_t retired_expansions_ = 0, main_base_ = 0, ahead_base_ = 0;
  Config current_;
  Config next_;
  GoalTest test_;
  const HNode* planned_ = nullptr;       // cache of planned() until the tree or root changes
  const HNode* promised_ = nullptr;      // what next() last returned: commit() moves there
  std::vector<float> carried_;           // priorities carried into a new epoch
  std::vector<int32_t> carried_order_;   // the agents' order under them
  std::vector<float> hint_, tie_;        // the task layer's priority hints; dist/N at the epoch start
  const Graph& g_;
  std::vector<uint8_t> immobile_;        // agent -> 1 while immobile
  uint64_t restarts_ = 0;
  LacamOptions opt_;                     // also for a lookahead's search; keep_priorities for restart()
  ActionPreference* pref_;
  std::vector<Vertex> pockets_;          // set_pockets', for a lookahead's search too
  float pocket_cost_ = 0;
};

}  // namespace planner
