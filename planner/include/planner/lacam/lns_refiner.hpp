#pragma once
// LnsRefiner: large-neighbourhood improvement of a path of configurations C^0..C^T (the
// refinement step of MAPF-LNS, Li et al. IJCAI-21, and of lacam3's refiner / Okumura's
// iterative refinement). One step picks a few agents -- a random delayed agent and random
// others -- and a random time window [t0, t0 + window] of the path, erases their moves in
// the window and replans them one by one with space-time A* around everybody else's (same
// positions at both ends of the window), and keeps the result only when their cost drops:
// under Objective::loss LaCAM*'s (per action, 0 while staying on the goal); under
// Objective::soc the standard SOC (objective.hpp): an agent that stays on its goal after the
// window is charged up to its last arrival in it, and its A* arrives once and stays (the goal
// must be free from then to the window's end, SIPP's rule in lacam3's refiner), so it is
// never parked where someone passes later; an agent that leaves its goal after the window
// costs the whole window whatever it does there (it is replanned only to make room, at the
// least loss). Ties in the standard SOC are broken by the loss: a step that keeps it and
// lowers the loss is kept too. The window keeps a step's cost small and
// independent of the path length (the occupancy table is window x |V|), so steps fit in a
// real-time budget. Every transition stays free of
// vertex and swap conflicts, so the new path is a valid chain of LaCAM configurations.
//
// Why here: LaCAM*'s rewiring alone improves large instances slowly (it needs PIBT to
// regenerate better configurations by chance); LaCAM* with LacamOptions::lns hands it the
// configurations of an improved path instead (Lacam inserts and rewires them).
#include <cstdint>
#include <functional>
#include <queue>
#include <string>
#include <tuple>
#include <vector>

#include "planner/budget.hpp"
#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"
#include "planner/lacam/lazy_table.hpp"
#include "planner/lacam/objective.hpp"
#include "planner/rng.hpp"

namespace planner {

// Neighbourhoods (MAPF-LNS, Li et al. IJCAI-21, Sec. 4), all seeded by a delayed agent
// (roulette by delay: only where someone waits or detours can the cost drop):
//  - random: random others;
//  - blocking (MAPF-LNS's agent-based one, made deterministic): the agents standing, one
//    step later, on a cell that would have brought a delayed agent closer to its goal
//    while it waited or detoured, then their blockers, breadth-first. Replanning a blocked
//    agent together with its whole blocking chain is what undoes an ordering in a
//    corridor, which fixing the others cannot;
//  - intersection: the agents that pass a vertex of degree >= 3 on the seed's path within
//    the window (they compete for the crossing);
//  - adaptive: roulette over the three by weights w <- g * (cost drop / |set|)
//    + (1 - g) * w on success, (1 - g) * w on failure (MAPF-LNS's ALNS, g = 0.01).
// Default random: at 1 ms per iteration the four are within 1 % of each other on
// random-32-32-20 / warehouse N=200/300 and random is best on the SUMO demo instance
// (docs/rt_lacam_star.md, scripts/bench_lns_neighbourhood.py).
enum class LnsNeighbourhood { random, blocking, intersection, adaptive };

class LnsRefiner {
 public:
  LnsRefiner(const Graph& g, DistTable& dist, int window = 32,
             LnsNeighbourhood nbh = LnsNeighbourhood::random, Objective obj = Objective::loss)
      : g_(g), dist_(dist), window_(window), max_window_(window), nbh_(nbh), obj_(obj) {}

  // path[0] and path.back() are fixed (a caller may pass a window of a longer path; the
  // delays that seed the neighbourhood are taken against its ends). Returns true when `path` was improved
  // (rewritten in place). Gives up (false) at `deadline`: a real-time caller's budget holds.
  // Under Objective::soc, `stays` (per agent, optional) says whether the agent stays on its
  // goal at every step after path.back() (a window of a longer path); null: path.back() is
  // the end, so an agent on its goal there stays. Under soc a neighbourhood also takes the
  // agents that pass the seed's goal in the window (they are what pushes it off). `seed`
  // (optional) is the agent the neighbourhood starts from, else a delayed one by roulette.
  bool step(std::vector<Config>& path, const Config& goals, int k, Rng& rng,
            Clock::time_point deadline = Clock::time_point::max(), const uint8_t* stays = nullptr, int seed = -1);
  // The agents the last step replanned.
  const std::vector<int>& last_set() const { return set_; }

  // Work of the last step, in visited cells and A* states (the cost pass over the path, the
  // occupancy table, the A* nodes and pops): a caller with a budget in expansions charges it.
  uint64_t work() const { return work_; }
  void set_window(int window) { window_ = window; }
  // Stop cost c (0: off): a move that starts from rest -- right after a wait, or a reversal
  // onto the cell the agent just left -- costs c more in the secondary cost (the loss under
  // soc, the cost under loss), so at an equal primary cost a step prefers plans an AGV can
  // drive without stopping (issue 21: a move from rest costs a physical executor ~2 s, a
  // chained one 1 s; lock-step pays nothing). The window's first move (no history) is free.
  void set_stop_cost(int c) { stop_cost_ = c < 0 ? 0 : c; }
  int stop_cost() const { return stop_cost_; }
  // Under soc: the secondary cost counts moves instead of the loss (waits are free: a physical
  // executor spends time on moves, and on waits only through what it waits for), so at an
  // equal standard SOC a step prefers waiting to detouring.
  void set_count_moves(bool on) { count_moves_ = on; }
  int window() const { return window_; }
  // The window x |V| tables are allocated once, for the largest window (the constructor's,
  // or a larger one set later), and their pages are mapped on first touch (lazy_table.hpp).
  // warm() maps the occupancy table ahead, for windows up to `window` steps, in pieces of 16
  // pages, and stops at `deadline`: true when done. A step writes all N agents' cells of
  // every step of its window there, so a real-time caller warms before it steps; the A*'s
  // tables (a few pages per step) fault in as they are used.
  bool warm(int window, Clock::time_point deadline);
  // The largest window whose occupancy table is mapped (-1: none).
  int warm_window() const;
  // Allocations of the tables so far (tests: one per table however the windows vary).
  long table_allocations() const { return occ_.allocations() + best_.allocations() + stamp_.allocations(); }
  // Heuristic of the last step (0 random, 1 blocking, 2 intersection) and the weights.
  int last_heuristic() const { return last_h_; }
  const double* weights() const { return weight_; }

  // Moves from rest (after a wait, or reversing) of agent i between steps t0 and t1, the
  // move out of t0 not counted (its history is outside the window).
  static int64_t agent_moves(const std::vector<Config>& path, int i, int t0, int t1);
  static int64_t agent_stops(const std::vector<Config>& path, int i, int t0, int t1);
  // LaCAM* cost (the loss) of agent i's path between steps t0 and t1.
  static int64_t agent_cost(const std::vector<Config>& path, const Config& goals, int i, int t0, int t1);
  // Standard SOC of agent i's path between steps t0 and t1 when it stays on its goal after
  // t1 (`stays`): the steps up to its last arrival; otherwise all t1 - t0 steps.
  static int64_t agent_soc(const std::vector<Config>& path, const Config& goals, int i, int t0, int t1, bool stays);

 private:
  int64_t cost_of(const std::vector<Config>& path, const Config& goals, int i, int t0, int t1, const uint8_t* stays) const;
  // `settle`: (soc) the agent stays on its goal after t1, so it arrives once and stays.
  bool replan(int i, const std::vector<Config>& path, const Config& goals, int t0, int t1, std::vector<Vertex>& out,
              Clock::time_point deadline, bool settle);

  // Fills set_ (the seed first) with up to k agents by heuristic h (0 random, 1 blocking,
  // 2 intersection); `cost` is every agent's cost over the whole path.
  void neighbourhood(int h, const std::vector<Config>& path, const Config& goals, const std::vector<int64_t>& cost,
                     int k, int t0, int t1, Rng& rng);

  // Allocates the tables for windows up to max(window_, max_window_) steps (once).
  void reserve_tables();

  const Graph& g_;
  DistTable& dist_;
  int window_;
  int stop_cost_ = 0;
  bool count_moves_ = false;
  int max_window_;  // the largest window the tables are allocated for
  LnsNeighbourhood nbh_;
  Objective obj_;
  double weight_[3] = {1.0, 1.0, 1.0};  // adaptive: ALNS weights of the three heuristics
  std::vector<int> set_;
  // Window x |V| tables, touched only where a step writes (lazy_table.hpp)
  LazyTable<int32_t> at_;   // blocking: 1 + agent at (t - t0, v) of the window, 0 none
  LazyTable<int32_t> occ_;  // ((t - t0) * |V| + v) -> 1 + agent there, 0 free
  std::vector<size_t> written_;   // occupied slots, to clear
  // replan()'s space-time A*, kept across calls (no allocation per step)
  struct AstarNode {
    Vertex v;
    int t;
    int64_t g;
    int32_t parent;
    bool stood;  // the agent waited on v the step before t (stop cost: its next move starts from rest)
  };
  using Item = std::tuple<int64_t, int, int32_t>;  // f, -t (deeper first), node
  std::vector<AstarNode> nodes_;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open_;
  // (t - t0) * |V| + v (+ one table of cells more for `stood` states under a stop cost)
  // -> best g, valid where stamp_ == epoch_
  LazyTable<int32_t> best_;
  LazyTable<uint32_t> stamp_;
  uint32_t epoch_ = 0;
  uint64_t clock_pops_ = 0;  // A* pops since construction: the deadline is read every 64
  uint64_t work_ = 0;
  int last_h_ = 0;
};

// "random" | "blocking" | "intersection" | "adaptive"; throws std::invalid_argument.
LnsNeighbourhood parse_lns_neighbourhood(const std::string& s);

}  // namespace planner
