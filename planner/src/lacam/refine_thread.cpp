#include "planner/lacam/refine_thread.hpp"

#include <algorithm>
#include <chrono>

#include "planner/lacam/iter_refiner.hpp"

namespace planner {

RefineThread::RefineThread(const Graph& g, int k, int window, LnsNeighbourhood nbh, uint64_t seed, bool iter)
    : g_(g), k_(k), window_(window), dist_(g), lns_(g, dist_, window, nbh, Objective::soc),
      iter_(iter ? std::make_unique<IterRefiner>(g, dist_, seed) : nullptr), rng_(seed), worker_([this] { run(); })
{
}

RefineThread::~RefineThread()
{
  {
    std::lock_guard<std::mutex> lk(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  worker_.join();
}

uint64_t RefineThread::post(std::vector<Config> path, int64_t step0, const Config& goals, int lead)
{
  {
    std::lock_guard<std::mutex> lk(mu_);
    posted_.swap(path);
    posted_step0_ = step0;
    posted_lead_ = std::max(kLead, lead);
    posted_goals_ = goals;
    posted_version_ = ++version_;
    executed_ = step0;
    if (posted_.empty()) out_.clear();  // parked (a reset): the old tree's windows are void
    fresh_ = true;
    idle_ = false;
  }
  cv_.notify_all();
  return version_;  // the old path's memory is freed here, outside the lock
}

void RefineThread::exchange(int64_t executed, std::vector<RefineWindow>& out)
{
  std::lock_guard<std::mutex> lk(mu_);
  executed_ = executed;
  for (RefineWindow& w : out_) out.push_back(std::move(w));
  out_.clear();
}

bool RefineThread::wait_published(double ms)
{
  std::unique_lock<std::mutex> lk(mu_);
  published_.wait_for(lk, std::chrono::duration<double, std::milli>(ms),
                      [&] { return !out_.empty() || (idle_ && !fresh_) || stop_; });
  return !out_.empty();
}

uint64_t RefineThread::improvements() const
{
  std::lock_guard<std::mutex> lk(mu_);
  return improvements_;
}

uint64_t RefineThread::steps() const
{
  std::lock_guard<std::mutex> lk(mu_);
  return steps_;
}

uint64_t RefineThread::iter_groups() const
{
  std::lock_guard<std::mutex> lk(mu_);
  return iter_groups_;
}

void RefineThread::run()
{
  // Failures in a row before the worker waits for a new job (LaCAM*'s LNS gives up alike).
  constexpr int kMaxFailures = 1000;
  Config goals;
  for (;;) {
    goals.clear();
    {
      std::unique_lock<std::mutex> lk(mu_);
      cv_.wait(lk, [&] { return stop_ || fresh_; });
      if (stop_) return;
      path_.swap(posted_);
      step0_ = posted_step0_;
      lead_ = posted_lead_;
      job_ = posted_version_;
      goals.swap(posted_goals_);
      fresh_ = false;
    }
    // Outside the lock: a new goal set may mean building distance tables (the worker's own:
    // DistTable is not shared), and the search must never wait for that.
    if (!goals.empty() && goals != goals_) {
      goals_ = goals;
      dist_.set_goals(goals_);
    }
    if (iter_) {
      run_iter();
      std::lock_guard<std::mutex> lk(mu_);
      idle_ = true;
      published_.notify_all();
      continue;
    }
    const int n = static_cast<int>(goals_.size());
    last_.assign(n, -1);
    for (size_t t = 0; t < path_.size(); ++t)
      for (int i = 0; i < n; ++i)
        if (path_[t][i] != goals_[i]) last_[i] = static_cast<int32_t>(t);
    int failures = 0;
    while (!path_.empty() && failures < kMaxFailures) {
      int64_t executed;
      {
        std::lock_guard<std::mutex> lk(mu_);
        if (stop_ || fresh_) break;
        executed = executed_;
      }
      bool improved = false;
      if (!step(executed, &improved)) break;  // the agents are past every window
      failures = improved ? 0 : failures + 1;
    }
    std::lock_guard<std::mutex> lk(mu_);
    idle_ = true;
    published_.notify_all();
  }
}

void RefineThread::run_iter()
{
  // A window every kEmit groups that lowered the cost, sooner when the change is near the
  // executed step; the worker gives up on a job once more than two passes' worth of agents
  // lowered nothing (IterRefiner::idle).
  constexpr uint64_t kEmit = 4;
  IterRefiner& R = *iter_;
  const int n = static_cast<int>(goals_.size());
  if (path_.empty() || n == 0) return;
  std::vector<const Vertex*> ptrs(path_.size());
  for (size_t t = 0; t < path_.size(); ++t) ptrs[t] = path_[t].data();
  R.reset(ptrs, n, step0_, goals_, job_);
  uint64_t since = 0;
  for (;;) {
    int64_t executed;
    {
      std::lock_guard<std::mutex> lk(mu_);
      if (stop_ || fresh_) return;
      executed = executed_;
    }
    R.step(executed + lead_, Clock::time_point::max());
    if (R.last_group() == 0) return;  // nothing left ahead of the agents
    ++since;
    RefineWindow w;
    const bool emit = R.cost() < R.emitted_cost() &&
                      (since >= kEmit || R.dirty_from() - executed < 2 * static_cast<int64_t>(lead_)) && R.window(w);
    std::lock_guard<std::mutex> lk(mu_);
    ++steps_;
    ++iter_groups_;
    if (emit) {
      since = 0;
      ++improvements_;
      if (!fresh_) {
        out_.push_back(std::move(w));
        published_.notify_all();
      }
    }
    if (R.idle() > 2 * n) return;
  }
}

// One LNS step as Lacam::lns_step's (soc): a delayed agent by roulette, a window that ends a
// little after its last arrival, but starting lead_ steps ahead of the executed step.
bool RefineThread::step(int64_t executed, bool* improved)
{
  const int n = static_cast<int>(goals_.size());
  const int T = static_cast<int>(path_.size()) - 1;
  const int off = static_cast<int>(std::max<int64_t>(0, executed - step0_));
  const int first = off + lead_;  // the earliest t0
  if (first >= T) return false;
  const Config& root = path_[std::min(off, T)];
  int64_t total = 0;
  for (int i = 0; i < n; ++i)
    if (last_[i] >= first) total += std::max<int64_t>(0, last_[i] + 1 - off - dist_.get(i, root[i]));
  if (total <= 0) return false;  // nobody delayed past the lead: nothing to gain
  int64_t r = static_cast<int64_t>(rng_.uniform() * static_cast<double>(total));
  int seed = -1;
  for (int i = 0; i < n && seed < 0; ++i) {
    if (last_[i] < first) continue;
    r -= std::max<int64_t>(0, last_[i] + 1 - off - dist_.get(i, root[i]));
    if (r < 0) seed = i;
  }
  if (seed < 0) return true;  // rounding: try again
  const int t1 = std::min(T, last_[seed] + 1 + static_cast<int>(rng_.below(static_cast<uint32_t>(window_ / 4 + 1))));
  const int t0 = std::max(std::min(first, t1 - 1), t1 - window_);
  const int W = t1 - t0;
  if (W < 1 || t0 < first) return true;
  win_.assign(path_.begin() + t0, path_.begin() + t1 + 1);
  stays_.resize(n);
  for (int i = 0; i < n; ++i) stays_[i] = last_[i] < t1;
  lns_.set_window(W);
  *improved = lns_.step(win_, goals_, k_, rng_, Clock::time_point::max(), stays_.data(), seed);
  RefineWindow w;
  if (*improved) {
    std::copy(win_.begin(), win_.end(), path_.begin() + t0);
    for (int i : lns_.last_set()) {
      if (last_[i] > t1) continue;  // leaves its goal after the window: unchanged
      last_[i] = -1;
      for (int t = t1; t >= 0; --t)
        if (path_[t][i] != goals_[i]) {
          last_[i] = t;
          break;
        }
    }
    w.version = job_;
    w.t0 = step0_ + t0;
    w.configs = win_;
    w.agents = lns_.last_set();
  }
  std::lock_guard<std::mutex> lk(mu_);
  ++steps_;
  if (*improved) {
    ++improvements_;
    if (!fresh_) {
      out_.push_back(std::move(w));
      published_.notify_all();
    }
  }
  return true;
}

}  // namespace planner
