#pragma once
// IterRefiner: iterative refinement of a whole plan (Okumura's iterative refinement, the
// refiner of lacam3: Okumura, AAMAS-24), in the search thread and resumable. It keeps its own
// copy of the followed path as one path per agent over the whole horizon, with a collision
// table (|V| x time -> agent) that lives across steps: a step replans one group of agents
// from a frozen step tf to the end -- each by SIPP around everybody else, to its goal as
// early as the table allows and free from then on -- and keeps the group's new paths when
// their standard SOC (each agent's last arrival) is not higher. Ties are kept too, as lacam3
// does: they move the plan across plateaus. Groups go through the agents in a shuffled
// order, a pass at a time, the group size drawn anew per pass (1..min(30, N/4), lacam3's).
//
// Why (issue 22): LnsRefiner (lns_refiner.hpp) rebuilds a window x N occupancy table for
// every step of k agents, so it replans few agents per millisecond, and it replans them
// inside a window with both ends fixed. Here a group costs its own A*s and table updates
// only, and each agent may arrive anywhere in the rest of the horizon. On
// warehouse-10-20-10-2-1 N = 500 lacam3's single refiner takes its first solution from 1.28
// to 1.15 x LB in 2.3 s, where the search's LNS took ours from 1.44 to 1.40 in 2.7 s.
//
// Steps are absolute (executed steps since the search's reset): the copy starts at step0 and
// the caller says, per step, from which step the agents may still be replanned (ahead of the
// executed one by the insertion's lead). The changes since the last window() are one range of
// steps [a, b]; window() hands it out with one unchanged configuration at each end, which is
// what Lacam inserts and splices (the refiner threads' RefineWindow). The horizon's length
// never changes: an agent that arrives earlier waits on its goal, and a group that would
// leave the last configuration but one on the goals is refused (the path would repeat the
// goal configuration).
#include <cstdint>
#include <queue>
#include <vector>

#include "planner/budget.hpp"
#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"
#include "planner/lacam/lazy_table.hpp"
#include "planner/lacam/refine_thread.hpp"
#include "planner/rng.hpp"

namespace planner {

class IterRefiner {
 public:
  IterRefiner(const Graph& g, DistTable& dist, uint64_t seed) : g_(g), dist_(dist), rng_(seed) {}

  // A new copy: path[0] is the configuration at absolute step `step0`, path.back() == goals.
  // O(T x N). `version` is the caller's name for the path copied (BestPath::version()).
  // `wait` (optional, per agent): steps it has stood on its goal before step0, charged if it
  // leaves it (BestPath's pricing): an agent's cost is 0 if it stays on its goal throughout,
  // else wait + its last arrival.
  void reset(const std::vector<const Vertex*>& path, int n, int64_t step0, const Config& goals, uint64_t version,
             const int32_t* wait = nullptr)
  {
    begin(path, n, step0, goals, version, wait);
    build(Clock::time_point::max());
  }
  // The same in slices (a real-time caller): begin() takes the path's configuration pointers
  // (O(T); they must stay valid until the copy is built), build() clears the old copy's cells
  // and enters the new one's, a time step at a time (O(N) each), until `deadline`; true once
  // the copy is ready.
  void begin(const std::vector<const Vertex*>& path, int n, int64_t step0, const Config& goals, uint64_t version,
             const int32_t* wait = nullptr);
  bool build(Clock::time_point deadline);
  bool ready() const { return ready_; }
  bool building() const { return !ready_ && !src_.empty(); }
  uint64_t version() const { return version_; }
  void set_version(uint64_t v) { version_ = v; }
  // Forget the copy (the caller's path changed in a way the copy does not follow); its cells
  // are cleared by the next begin().
  void clear()
  {
    ready_ = false;
    src_.clear();
    version_ = UINT64_MAX;
  }

  // One group, replanned from absolute step `from` on (positions at `from` fixed). Returns
  // true when the group's new paths were kept; false when they were not, when no step is
  // left to replan, or at `deadline` (nothing changed then).
  // At most `max_agents` of the pass's group size.
  bool step(int64_t from, Clock::time_point deadline, int max_agents = 1 << 30);
  int last_group() const { return last_group_; }  // agents the last step() tried (0: none)
  // Agents replanned since the cost last dropped (or since the copy).
  int idle() const { return idle_; }
  // Every agent was replanned four times since the cost last dropped (or since the copy):
  // the passes found nothing, and the caller may refine otherwise for a while. (One pass
  // was too soon: on random-32-32-20 N = 400 LNS then took turns the passes would have used,
  // 10-12 % costlier at 10 s; two passes 5 %, four none.)
  bool stale() const { return ready_ && idle_ >= 4 * n_; }
  // The first absolute step changed since the last window() (-1: none).
  int64_t dirty_from() const { return dirty_a_ < 0 ? -1 : step0_ + dirty_a_; }
  int dirty_steps() const { return dirty_a_ < 0 ? 0 : dirty_b_ - dirty_a_ + 3; }  // a window's configurations
  // Standard SOC of the copy, and of the copy at the last window() (or reset).
  int64_t cost() const { return cost_; }
  int64_t emitted_cost() const { return emitted_cost_; }
  // The configurations over [a - 1, b + 1] where [a, b] are the steps changed since the last
  // window() (or reset), the agents whose moves changed there, and the copy's version. False
  // when nothing changed. The copy counts as emitted from then on.
  bool window(RefineWindow& out);

  // Work of the copy since begin() in table cells: a caller with a budget in expansions
  // charges it.
  uint64_t work() const { return work_; }
  uint64_t groups() const { return groups_; }
  uint64_t kept() const { return kept_; }

 private:
  // vertex-major: a vertex's steps are contiguous
  int32_t& occ(int t, Vertex v) { return occ_[static_cast<size_t>(v) * S_ + static_cast<size_t>(t)]; }
  // time-major, as the configurations come
  Vertex at(int i, int t) const { return paths_[static_cast<size_t>(t) * n_ + i]; }
  Vertex& at(int i, int t) { return paths_[static_cast<size_t>(t) * n_ + i]; }
  int arrival_by(int i, int t) const;  // 1 + agent i's last step <= t off its goal; 0: none
  int64_t cost_of(int i, int arrival) const { return arrival > 0 ? arrival + wait_[i] : 0; }
  // SIPP (safe-interval path planning, Phillips & Likhachev ICRA-11, as lacam3's refiner) for
  // agent i from (at(i, tf), tf) to its goal, free from its arrival to T_; the least arrival
  // <= bound. Writes the path over [tf, T_] into out.
  bool replan(int i, int tf, int64_t bound, std::vector<Vertex>& out, Clock::time_point deadline);
  void new_pass();
  bool clear_old(Clock::time_point deadline);

  const Graph& g_;
  DistTable& dist_;
  Rng rng_;
  int n_ = 0;
  int T_ = 0;
  size_t V_ = 0;
  int64_t step0_ = 0;
  uint64_t version_ = 0;
  Config goals_;
  std::vector<Vertex> paths_;      // time-major: paths_[t * N + i]
  bool ready_ = false;
  std::vector<const Vertex*> src_; // begin()'s configurations, entered by build()
  int row_ = 0;                    // the next of them
  std::vector<Vertex> old_;        // the copy before, time-major, while its cells are cleared
  int old_n_ = 0, old_T_ = -1, old_row_ = 0;
  size_t old_S_ = 0;
  std::vector<int32_t> arrival_;   // per agent, relative to step0
  std::vector<int32_t> wait_;      // per agent: reset()'s wait
  int last_group_ = 0;
  int idle_ = 0;                   // agents replanned since the cost last dropped
  LazyTable<int32_t> occ_;         // |V| x (T + 1) -> 1 + agent, 0 free
  std::vector<std::vector<int32_t>> times_;  // per vertex: its occupied steps, ascending
  void put(int t, Vertex v, int i);  // agent i on v at t (occ_ and times_)
  void take(int t, Vertex v);
  size_t S_ = 0;                   // occ_'s stride: T_ + 1
  int64_t cost_ = 0, emitted_cost_ = 0;
  int dirty_a_ = -1, dirty_b_ = -1;  // relative steps changed since the last window()
  std::vector<uint8_t> moved_;     // per agent: changed since the last window()
  // the pass
  std::vector<int> order_;
  size_t next_ = 0;
  int group_ = 1;
  // SIPP: each vertex's safe intervals over [tf, T_], built when first reached in a replan
  std::vector<uint32_t> stamp_;    // per vertex: the replan its intervals are of
  std::vector<int32_t> first_;     // per vertex: its first interval in ivl_
  std::vector<int32_t> count_;     // per vertex: how many
  struct Interval {
    int lo, hi;      // free steps [lo, hi]
    int best;        // earliest arrival found (INT_MAX: none)
  };
  std::vector<Interval> ivl_;
  uint32_t epoch_ = 0;
  void intervals(int i, Vertex v, int tf);
  struct Node {
    Vertex v;
    int t;           // arrival
    int32_t ivl;     // its interval in ivl_
    int32_t parent;
  };
  std::vector<Node> nodes_;
  using Item = std::pair<int64_t, int32_t>;  // (f, d, -t) packed (replan), node
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open_;
  std::vector<std::vector<Vertex>> fresh_;
  uint64_t work_ = 0, groups_ = 0, kept_ = 0, clock_ = 0;
};

}  // namespace planner
