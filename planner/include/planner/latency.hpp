#pragma once
// Latency: the summary of a sample of durations (milliseconds) that every layer reports --
// the bench's iteration times, a lifelong run's planner times per step, the controller's
// per-step and per-tick times -- with one definition of its percentiles: nearest rank, the
// smallest sample such that at least q of all samples are <= it (p99 of 100 samples is the
// 99th smallest, of 10 samples the largest).
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace planner {

class LatencySample;

struct Latency {
  long long count = 0;
  double mean = 0, p50 = 0, p99 = 0, max = 0;  // all 0 for no samples

  static Latency of(std::vector<double> ms);
  // A template so that of({...}) still means the vector (a braced list deduces nothing).
  template <class S, class = std::enable_if_t<std::is_same_v<S, LatencySample>>>
  static Latency of(const S& s)
  {
    return of_sample(s);
  }
  static Latency of_sample(const LatencySample& s);
};

// Durations of a run of any length in bounded memory (a lifelong run's millions of SUMO
// steps): count, mean and max stay exact; the percentiles are exact up to `cap` samples,
// beyond that they are those of a uniform reservoir of `cap` (Vitter's algorithm R, fixed
// seed: the same run gives the same numbers). Vector-like where the controller uses it:
// push_back, back() (the last sample can still be added to), empty. The default cap, 16384
// samples (128 KB), is reached after ~2000 ticks of 8 SUMO steps; a p99 from a reservoir
// that size is within about +-0.15 percentile points. (At 65536 each per-step sample of the
// controller grew until tick 8192, to 0.5 MB: part of a long run's RSS growth.)
class LatencySample {
 public:
  explicit LatencySample(std::size_t cap = 1 << 14) : cap_(cap) {}
  void push_back(double ms);
  double& back() { return last_; }  // the latest sample (committed at the next push_back)
  bool empty() const { return count_ == 0; }
  long long size() const { return count_; }

 private:
  friend struct Latency;
  void commit(double ms);
  std::size_t cap_;
  long long count_ = 0;  // pushed, the pending last one included
  double last_ = 0, sum_ = 0, max_ = 0;
  std::vector<double> kept_;
  uint64_t rng_ = 0x9e3779b97f4a7c15ULL;
};

// The nearest-rank q-quantile (0 < q <= 1) of a non-empty sample; 0 for an empty one.
double nearest_rank(std::vector<double> ms, double q);

}  // namespace planner
