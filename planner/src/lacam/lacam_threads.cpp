// The search's side of the refiner threads (LacamOptions::refine_threads, refine_thread.hpp):
// it posts the followed path to the workers (when it changed and a few moves passed), and
// adopts their windows at its iteration boundaries. A window is adopted only when
//  - it starts at least one step ahead of the root on the followed path and ends on it, with
//    the same configurations at both ends (the agents have not passed it; the worker's copy
//    may be older than the path, but there the two agree),
//  - the validator accepts every transition of the part that differs (adjacency, vertex and
//    swap conflicts), and
//  - the followed path with it is not costlier: it is inserted node by node like an LNS
//    window of the search's own (insert_step) and spliced in by BestPath::splice, priced for
//    every agent whose moves differ, which refuses it if the standard SOC would rise.
// Every step here is gated by its learnt cost (step_cost.hpp) like the search's other
// refinement steps; the search's own LNS goes on as without workers.
#include <algorithm>
#include <limits>

#include "planner/lacam/lacam.hpp"
#include "planner/lacam/refine_thread.hpp"
#include "planner/validator.hpp"

namespace planner {

// Priors until measured (ms per configuration x agent): a copy is a memcpy (~1 ns an agent),
// a validated transition a few table reads and writes. Learnt from the first step on.
constexpr double kPostPrior = 2e-6, kCheckPrior = 2e-5;
// A worker's copy is posted anew once the followed path changed and this many moves passed
// since its last post: the search's own LNS changes the path every other iteration, and a
// post costs a copy of the path (configurations x agents).
constexpr int64_t kRepostSteps = 2;

struct Lacam::Threads {
  static constexpr uint64_t kNone = std::numeric_limits<uint64_t>::max();
  std::vector<std::unique_ptr<RefineThread>> workers;
  std::vector<uint64_t> synced;   // per worker: the BestPath version its copy was (kNone: none)
  std::vector<int64_t> posted_at; // per worker: root_step_ at its last post
  std::vector<RefineWindow> taken;  // windows taken at the last exchange, in order
  std::vector<int> source;        // their workers
  size_t next = 0;
  int adopting = -1;              // the worker whose window is being inserted
  int64_t cost0 = 0;              // the followed path's cost before it
  uint64_t windows = 0, wins = 0, refused = 0, posts = 0;
  std::vector<std::pair<int64_t, int64_t>> adoptions;
  StepCost check_cost, post_cost;  // per configuration x agent validated / copied
};

Lacam::~Lacam() = default;

void Lacam::ThreadsDeleter::operator()(Threads* t) const { delete t; }

void Lacam::start_threads()
{
  if (!opt_.refine || opt_.refine_threads <= 0) return;
  threads_.reset(new Threads);
  for (int j = 0; j < opt_.refine_threads; ++j)
    threads_->workers.push_back(std::make_unique<RefineThread>(g_, opt_.lns_agents, opt_.lns_window,
                                                               opt_.lns_neighbourhood, opt_.seed + 101 + j, opt_.iter_refine));
  threads_->synced.assign(opt_.refine_threads, Threads::kNone);
  threads_->posted_at.assign(opt_.refine_threads, 0);
}

uint64_t Lacam::thread_windows() const { return threads_ ? threads_->windows : 0; }
uint64_t Lacam::thread_wins() const { return threads_ ? threads_->wins : 0; }
uint64_t Lacam::thread_refused() const { return threads_ ? threads_->refused : 0; }
uint64_t Lacam::thread_posts() const { return threads_ ? threads_->posts : 0; }

uint64_t Lacam::refiner_improvements() const
{
  uint64_t k = 0;
  if (threads_)
    for (const auto& w : threads_->workers) k += w->improvements();
  return k;
}

uint64_t Lacam::refiner_iter_groups() const
{
  uint64_t k = 0;
  if (threads_)
    for (const auto& w : threads_->workers) k += w->iter_groups();
  return k;
}

std::vector<std::pair<int64_t, int64_t>> Lacam::thread_adoptions() const
{
  return threads_ ? threads_->adoptions : std::vector<std::pair<int64_t, int64_t>>{};
}

void Lacam::wait_refiners(double ms) const
{
  if (threads_)
    for (const auto& w : threads_->workers) w->wait_published(ms);
}

void Lacam::threads_park()
{
  if (!threads_) return;
  Threads& T = *threads_;
  for (size_t j = 0; j < T.workers.size(); ++j)
    if (T.synced[j] != Threads::kNone) T.workers[j]->post({}, 0, goals_);
  T.synced.assign(T.workers.size(), Threads::kNone);
  T.taken.clear();
  T.source.clear();
  T.next = 0;
  T.adopting = -1;
}

void Lacam::threads_exchange()
{
  Threads& T = *threads_;
  if (T.next >= T.taken.size()) {
    T.taken.clear();
    T.source.clear();
    T.next = 0;
  }
  for (size_t j = 0; j < T.workers.size(); ++j) {
    if (T.synced[j] == Threads::kNone) continue;
    T.workers[j]->exchange(root_step_, T.taken);
    T.source.resize(T.taken.size(), static_cast<int>(j));
  }
}

bool Lacam::thread_step()
{
  Threads& T = *threads_;
  const auto& p = best_.nodes();
  while (T.next < T.taken.size()) {
    const int j = T.source[T.next];
    const int r = place_window(T.taken[T.next], T.check_cost);
    if (r == 0) return false;  // later, when an iteration has room
    ++T.next;
    if (r < 0) {
      ++T.refused;
      if (r == -2) return true;  // its check took the turn
      continue;
    }
    T.adopting = j;
    T.cost0 = best_.cost();
    if (!timed_) insert_step();  // no deadline: at once (deterministic runs)
    return true;
  }
  // Post the followed path to a worker that has none, or whose copy is older and
  // kRepostSteps moves old (its windows still apply where the two paths agree).
  const uint64_t now = best_.version();
  for (size_t j = 0; j < T.workers.size(); ++j) {
    if (T.synced[j] == now || (T.synced[j] != Threads::kNone && root_step_ - T.posted_at[j] < kRepostSteps)) continue;
    const double units = static_cast<double>(p.size()) * n_;
    T.post_cost.set_prior(kPostPrior);
    if (timed_ && !fits(T.post_cost.predict_ms(units))) {
      T.post_cost.forget();
      return false;
    }
    const double c0 = timed_ ? thread_cpu_ms() : 0.0;
    std::vector<Config> path;
    path.reserve(p.size());
    for (const HNode* h : p) path.emplace_back(h->C, h->C + n_);
    T.workers[j]->post(std::move(path), root_step_, goals_);
    T.synced[j] = now;
    T.posted_at[j] = root_step_;
    ++T.posts;
    if (timed_) T.post_cost.record(units, thread_cpu_ms() - c0);
    return true;
  }
  return false;
}

int Lacam::place_window(RefineWindow& w, StepCost& check_cost, bool trusted)
{
  const auto& p = best_.nodes();
  const int64_t k = w.t0 - root_step_;
  const int64_t W = static_cast<int64_t>(w.configs.size()) - 1;
  if (k < 1 || W < 2 || k + W >= static_cast<int64_t>(p.size()) ||
      !config_equal(p[k]->C, w.configs.front().data(), n_) || !config_equal(p[k + W]->C, w.configs.back().data(), n_))
    return -1;  // the agents are past it, or the followed path changed there
#ifdef NDEBUG
  if (trusted) {  // its own copy of this very path: the changed steps and agents are known
    pending_.assign(std::make_move_iterator(w.configs.begin()), std::make_move_iterator(w.configs.end()));
    pending_next_ = 1;
    pending_prev_ = splice_from_ = p[k];
    spliced_.clear();
    splice_set_ = w.agents;
    return 1;
  }
#endif
  const double units = static_cast<double>(W) * n_;
  check_cost.set_prior(kCheckPrior);
  if (timed_ && !fits(check_cost.predict_ms(units))) {
    check_cost.forget();
    return 0;
  }
  const double c0 = timed_ ? thread_cpu_ms() : 0.0;
  // The agents whose moves differ from the followed path's, and the steps [a, b] where
  // any does: only those are inserted (the refiner's copy may be older than the path).
  std::vector<uint8_t> moved(n_, 0);
  int64_t a = W, b = 0;
  for (int64_t t = 1; t < W; ++t) {
    const Vertex* C = p[k + t]->C;
    bool differs = false;
    for (int i = 0; i < n_; ++i)
      if (C[i] != w.configs[t][i]) moved[i] = 1, differs = true;
    if (differs) a = std::min(a, t), b = std::max(b, t);
  }
  bool valid = a <= b;  // else nothing new
  if (valid) {
    Validator v(g_, w.configs[a - 1], goals_);
    for (int64_t t = a; t <= b + 1 && valid; ++t) valid = v.step(w.configs[t]);
  }
  if (timed_) check_cost.record(units, thread_cpu_ms() - c0);
  if (!valid) return -2;
  pending_.assign(std::make_move_iterator(w.configs.begin() + (a - 1)),
                  std::make_move_iterator(w.configs.begin() + (b + 2)));
  pending_next_ = 1;
  pending_prev_ = splice_from_ = p[k + a - 1];
  spliced_.clear();
  splice_set_.clear();
  for (int i = 0; i < n_; ++i)
    if (moved[i]) splice_set_.push_back(i);
  return 1;
}

void Lacam::thread_spliced(bool ok)
{
  Threads& T = *threads_;
  const int j = T.adopting;
  if (j < 0) return;  // the search's own window
  T.adopting = -1;
  if (!ok) {  // costlier on the followed path than on the worker's copy
    ++T.refused;
    return;
  }
  ++T.windows;
  if (best_.cost() < T.cost0) ++T.wins;
  T.adoptions.emplace_back(T.cost0, best_.cost());
}

}  // namespace planner
