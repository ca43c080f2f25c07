#pragma once
// RefineThread: a refiner thread that runs LNS (lns_refiner.hpp, standard SOC) on its own
// copy of RT-LaCAM*'s followed path, concurrently with the search (lacam3's refiner threads,
// Okumura AAMAS-24; issue 22). The search thread (Lacam, LacamOptions::refine_threads) stays
// the only one that touches the tree and the agents' plan: it posts a copy of the followed
// path, and adopts the worker's improved windows at an iteration boundary, only when each
// still starts ahead of the executed configuration on the path it follows and passes the
// validator (lacam_threads.cpp). So the search thread's per-iteration work is a lock, a swap
// and steps gated by its budget, as before; the LNS steps' CPU is the worker's.
//
// Shared state, all under one mutex: the posted job (path, its first step, goals), the
// executed step, the windows published and a stop flag. The worker owns everything else (its
// path, DistTable, LnsRefiner, Rng): nothing mutable is shared outside the lock.
//
// A window is the worker's path over [t0, t0 + W] after one improving LNS step, t0 counted in
// executed steps since the search's reset (absolute), so that the search can place it on its
// own path however far the agents moved meanwhile. The worker applies its windows to its copy;
// the search makes LNS steps of its own too, so its path drifts from the copy: it adopts a
// window where the two paths agree at both ends, validated and priced for every agent whose
// moves differ (lacam_threads.cpp), and posts its path again once it changed and a few moves
// passed. Windows start at least kLead steps ahead of the last executed step the worker
// knows, so that the search can insert them before the agents get there.
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"
#include "planner/lacam/lns_refiner.hpp"
#include "planner/rng.hpp"

namespace planner {

class IterRefiner;

struct RefineWindow {
  uint64_t version = 0;            // the job it improves
  int64_t t0 = 0;                  // absolute step of configs[0]
  std::vector<Config> configs;     // the path over [t0, t0 + W]; both ends unchanged
  std::vector<int> agents;         // the agents it replanned (the others kept their moves)
};

class RefineThread {
 public:
  static constexpr int kLead = 8;  // a window starts at least this far ahead of the executed step

  // k agents per LNS step, windows of up to `window` steps; the worker starts idle. `iter`:
  // the worker runs iterative refinement (iter_refiner.hpp) on its copy instead of LNS, and
  // publishes the steps it changed as one window every few groups (LacamOptions::iter_refine).
  RefineThread(const Graph& g, int k, int window, LnsNeighbourhood nbh, uint64_t seed, bool iter = false);
  ~RefineThread();  // stops the worker (after its running step) and joins it
  RefineThread(const RefineThread&) = delete;
  RefineThread& operator=(const RefineThread&) = delete;

  // Search thread. A new job: `path` (the followed path; path[0] is the configuration at
  // absolute step `step0`) towards `goals`; windows start at least max(kLead, lead) steps
  // ahead of the executed step (the search's insertion takes that long). Returns its
  // version. An empty path parks the worker (a reset) and drops the windows not taken.
  uint64_t post(std::vector<Config> path, int64_t step0, const Config& goals, int lead = kLead);
  // Tells the worker the last executed step, and moves the windows published since into
  // `out` (appended, in order). One lock.
  void exchange(int64_t executed, std::vector<RefineWindow>& out);
  uint64_t version() const { return version_; }  // of the last post() (search thread only)

  // Tests: blocks until a window of the current job is published or the worker gave up on
  // it (idle), at most `ms`. True if a window is waiting.
  bool wait_published(double ms);
  // Improving steps, and steps, the worker made (all jobs).
  uint64_t improvements() const;
  uint64_t steps() const;
  uint64_t iter_groups() const;  // iter mode: groups replanned (all jobs); 0 in LNS mode

 private:
  void run();
  // One LNS step on path_ (returns false when no window fits ahead of `executed`).
  bool step(int64_t executed, bool* improved);
  // iter: refines the job with iter_ until a new job or stop (or nothing is left ahead).
  void run_iter();

  const Graph& g_;
  const int k_;
  const int window_;
  // Worker-only state
  DistTable dist_;
  LnsRefiner lns_;
  std::unique_ptr<IterRefiner> iter_;  // iter mode
  Rng rng_;
  std::vector<Config> path_;
  Config goals_;
  int64_t step0_ = 0;
  int lead_ = kLead;
  uint64_t job_ = 0;                // version of path_
  std::vector<int32_t> last_;       // per agent: last index of path_ off its goal (-1 none)
  std::vector<Config> win_;         // scratch: a window
  std::vector<uint8_t> stays_;
  // Shared, under mu_
  mutable std::mutex mu_;
  std::condition_variable cv_;       // the worker waits for a job or stop
  std::condition_variable published_;  // tests wait for a window
  bool stop_ = false, fresh_ = false, idle_ = true;
  std::vector<Config> posted_;
  int64_t posted_step0_ = 0;
  int posted_lead_ = kLead;
  Config posted_goals_;
  uint64_t posted_version_ = 0;
  int64_t executed_ = 0;
  std::vector<RefineWindow> out_;
  uint64_t improvements_ = 0, steps_ = 0, iter_groups_ = 0;
  // Search thread only
  uint64_t version_ = 0;
  std::thread worker_;  // last: starts once everything above is built
};

}  // namespace planner
