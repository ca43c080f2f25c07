#pragma once
// Latency: the summary of a sample of durations (milliseconds) that every layer reports --
// the bench's iteration times, a lifelong run's planner times per step, the controller's
// per-step and per-tick times -- with one definition of its percentiles: nearest rank, the
// smallest sample such that at least q of all samples are <= it (p99 of 100 samples is the
// 99th smallest, of 10 samples the largest).
#include <vector>

namespace planner {

struct Latency {
  long long count = 0;
  double mean = 0, p50 = 0, p99 = 0, max = 0;  // all 0 for no samples

  static Latency of(std::vector<double> ms);
};

// The nearest-rank q-quantile (0 < q <= 1) of a non-empty sample; 0 for an empty one.
double nearest_rank(std::vector<double> ms, double q);

}  // namespace planner
