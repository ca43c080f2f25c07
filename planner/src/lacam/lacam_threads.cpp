// The search's side of the refiner threads (LacamOptions::refine_threads, refine_thread.hpp):
// it posts the followed path to each worker whose copy is no longer that path, and adopts
// the workers' windows at its iteration boundaries. A window is adopted only when
//  - its worker's copy is still the followed path (the same BestPath version, the same job),
//  - it starts at least one step ahead of the root on that path and ends on it, with the
//    same configurations at both ends (the agents have not passed it), and
//  - the validator accepts every transition in it (adjacency, vertex and swap conflicts);
// it is then inserted node by node like an LNS window of the search's own (insert_step) and
// spliced into the followed path, which BestPath::splice refuses if it were costlier. Any
// refusal makes the search post the path again. Every step here is gated by its learnt
// cost (step_cost.hpp) like the search's other refinement steps.
#include <algorithm>
#include <limits>

#include "planner/lacam/lacam.hpp"
#include "planner/lacam/refine_thread.hpp"
#include "planner/validator.hpp"

namespace planner {

struct Lacam::Threads {
  static constexpr uint64_t kNone = std::numeric_limits<uint64_t>::max();
  std::vector<std::unique_ptr<RefineThread>> workers;
  std::vector<uint64_t> synced;   // per worker: the BestPath version its copy equals (kNone: none)
  std::vector<RefineWindow> taken;  // windows taken at the last exchange, in order
  std::vector<int> source;        // their workers
  size_t next = 0;
  int adopting = -1;              // the worker whose window is being inserted
  int64_t cost0 = 0;              // the followed path's cost before it
  uint64_t windows = 0, wins = 0, refused = 0;
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
                                                               opt_.lns_neighbourhood, opt_.seed + 101 + j));
  threads_->synced.assign(opt_.refine_threads, Threads::kNone);
}

uint64_t Lacam::thread_windows() const { return threads_ ? threads_->windows : 0; }
uint64_t Lacam::thread_wins() const { return threads_ ? threads_->wins : 0; }
uint64_t Lacam::thread_refused() const { return threads_ ? threads_->refused : 0; }

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
  const uint64_t now = best_.version();
  const auto& p = best_.nodes();
  while (T.next < T.taken.size()) {
    RefineWindow& w = T.taken[T.next];
    const int j = T.source[T.next];
    if (w.version != T.workers[j]->version() || T.synced[j] != now) {  // of an older path: dropped
      ++T.next;
      continue;
    }
    const int64_t k = w.t0 - root_step_;
    const int64_t W = static_cast<int64_t>(w.configs.size()) - 1;
    if (k < 1 || W < 1 || k + W >= static_cast<int64_t>(p.size()) ||
        !config_equal(p[k]->C, w.configs.front().data(), n_) || !config_equal(p[k + W]->C, w.configs.back().data(), n_)) {
      ++T.refused;  // the agents are past it (or it does not fit the path): the worker starts again
      T.synced[j] = Threads::kNone - 1;
      ++T.next;
      continue;
    }
    const double units = static_cast<double>(W) * n_;
    T.check_cost.set_prior(expand_cost_.rate() / std::max(n_, 1));
    if (timed_ && !fits(T.check_cost.predict_ms(units))) {
      T.check_cost.forget();
      return false;  // later, when an iteration has room
    }
    const double c0 = timed_ ? thread_cpu_ms() : 0.0;
    Validator v(g_, w.configs.front(), goals_);
    bool valid = true;
    for (int64_t t = 1; t <= W && valid; ++t) valid = v.step(w.configs[t]);
    if (timed_) T.check_cost.record(units, thread_cpu_ms() - c0);
    ++T.next;
    if (!valid) {
      ++T.refused;
      T.synced[j] = Threads::kNone - 1;
      return true;
    }
    pending_.swap(w.configs);
    pending_next_ = 1;
    pending_prev_ = splice_from_ = p[k];
    spliced_.clear();
    splice_set_.swap(w.agents);
    T.adopting = j;
    T.cost0 = best_.cost();
    if (!timed_) insert_step();  // no deadline: at once (deterministic runs)
    return true;
  }
  // Post the followed path to a worker whose copy is another one.
  for (size_t j = 0; j < T.workers.size(); ++j) {
    if (T.synced[j] == now) continue;
    const double units = static_cast<double>(p.size()) * n_;
    T.post_cost.set_prior(expand_cost_.rate() / std::max(n_, 1));
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
    if (timed_) T.post_cost.record(units, thread_cpu_ms() - c0);
    return true;
  }
  return false;
}

void Lacam::thread_spliced(bool ok)
{
  Threads& T = *threads_;
  const int j = T.adopting;
  if (j < 0) return;  // the search's own window
  T.adopting = -1;
  if (!ok) {
    ++T.refused;
    T.synced[j] = Threads::kNone - 1;
    return;
  }
  // The followed path is the worker's copy again: its later windows apply to it.
  T.synced[j] = best_.version();
  ++T.windows;
  if (best_.cost() < T.cost0) ++T.wins;
  T.adoptions.emplace_back(T.cost0, best_.cost());
}

}  // namespace planner
