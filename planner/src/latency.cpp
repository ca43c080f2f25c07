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

}  // namespace planner
