#pragma once
// CostEstimate: a running estimate of a repeated job's cost (ms) and of how much one run
// may exceed it, from the smoothed mean and mean deviation of its samples: Jacobson and
// Karels' round-trip estimator, the rule of TCP's retransmission timeout (RFC 6298:
// gain 1/8 for the mean, 1/4 for the deviation, bound = mean + 4 deviations).
//
// The lifelong runner times a search expansion with it. The search checks its deadline
// only between expansions, and an expansion (PIBT over every agent) cannot stop halfway,
// so the step must reserve a whole expansion before its deadline. A moving average is
// exceeded by every expansion above average, and those steps overran the budget; the
// bound is exceeded rarely (a jump in cost, which the deviation then absorbs).
#include <algorithm>
#include <cmath>

namespace tasks {

struct CostEstimate {
  double mean = 0;
  double dev = 0;
  long samples = 0;

  bool known() const { return samples > 0; }
  // What one more run may cost: mean + k deviations (0 before any sample).
  double bound(double k = 4) const { return mean + k * dev; }

  void add(double x)
  {
    if (samples++ == 0) {  // RFC 6298's first measurement: deviation = half the sample
      mean = x;
      dev = x / 2;
      return;
    }
    dev += 0.25 * (std::abs(x - mean) - dev);
    mean += 0.125 * (x - mean);
  }
};

}  // namespace tasks
