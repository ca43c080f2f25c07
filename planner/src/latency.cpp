#include "planner/latency.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace planner {
namespace {

// k-th smallest with k = ceil(q n) (1-based), on a sorted sample.
double rank_of_sorted(const std::vector<double>& sorted, double q)
{
  const double n = static_cast<double>(sorted.size());
  const size_t k = static_cast<size_t>(std::max(1.0, std::ceil(q * n - 1e-9)));
  return sorted[std::min(sorted.size(), k) - 1];
}

}  // namespace

double nearest_rank(std::vector<double> ms, double q)
{
  if (ms.empty()) return 0;
  std::sort(ms.begin(), ms.end());
  return rank_of_sorted(ms, q);
}

Latency Latency::of(std::vector<double> ms)
{
  Latency l;
  l.count = static_cast<long long>(ms.size());
  if (ms.empty()) return l;
  std::sort(ms.begin(), ms.end());
  l.mean = std::accumulate(ms.begin(), ms.end(), 0.0) / static_cast<double>(ms.size());
  l.p50 = rank_of_sorted(ms, 0.50);
  l.p99 = rank_of_sorted(ms, 0.99);
  l.max = ms.back();
  return l;
}

void LatencySample::commit(double ms)
{
  const long long n = count_ - 1;  // samples committed before this one
  sum_ += ms;
  if (n == 0 || ms > max_) max_ = ms;
  if (kept_.size() < cap_) {
    kept_.push_back(ms);
    return;
  }
  rng_ ^= rng_ << 13;  // xorshift64: deterministic, no <random> state to carry
  rng_ ^= rng_ >> 7;
  rng_ ^= rng_ << 17;
  const uint64_t j = rng_ % static_cast<uint64_t>(n + 1);
  if (j < cap_) kept_[j] = ms;
}

void LatencySample::push_back(double ms)
{
  if (count_ > 0) commit(last_);
  last_ = ms;
  ++count_;
}

Latency Latency::of_sample(const LatencySample& s)
{
  if (s.count_ == 0) return Latency{};
  LatencySample c = s;
  c.commit(c.last_);
  Latency l = of(c.kept_);
  l.count = c.count_;
  l.mean = c.sum_ / static_cast<double>(c.count_);
  l.max = c.max_;
  return l;
}

}  // namespace planner
