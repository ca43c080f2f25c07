#pragma once
// StepCost: predicts what a refinement step will cost (thread CPU ms) from its size, so that
// Lacam starts a step only when it fits what is left of the iteration's budget (and cuts a
// step that has a size, such as an LNS window, to fit). The rate (ms per unit) is learnt from
// the steps measured so far as a decaying maximum: a step that proved dearer is believed at
// once, a cheaper one lowers the rate slowly, so one lucky step does not let the next overrun.
// A step that was not started because it did not fit calls forget(): the rate decays then too,
// or one spike (a page fault, a preempted measurement) would keep a step out for good -- SUO
// never finished a pass at 10 ms per iteration before this (warehouse-10-20-10-2-1 N = 400).
// A prior (set_prior, re-set by the callers while nothing is measured, since it follows
// another step's rate) decays the same way: forget() before the first sample scales every
// later prior down. Without this a step whose prior never fits is never tried, so never
// measured: LNS at warehouse-10-20-10-2-1 N = 500, 1 ms, whose prior (an expansion per time
// step, 0.0003 ms per unit) was 10x its measured rate, made no step in a whole run.
#include <algorithm>

namespace planner {

class StepCost {
 public:
  explicit StepCost(double prior_ms_per_unit = 0) : rate_(prior_ms_per_unit) {}

  double predict_ms(double units) const { return units * rate_; }
  // Units that fit in `ms` (infinite while nothing is known and there is no prior).
  double units_within(double ms) const { return rate_ > 0 ? ms / rate_ : 1e300; }
  void record(double units, double ms)
  {
    if (units <= 0) return;
    const double r = ms / units;
    rate_ = r >= rate_ ? r : rate_ + kDecay * (r - rate_);
    ++samples_;
  }
  void forget()
  {
    rate_ *= 1 - kDecay;
    if (samples_ == 0) prior_scale_ *= 1 - kDecay;
  }
  void set_prior(double ms_per_unit) { if (samples_ == 0) rate_ = ms_per_unit * prior_scale_; }
  double rate() const { return rate_; }
  long samples() const { return samples_; }

 private:
  static constexpr double kDecay = 0.05;  // about 20 steps to forget a spike
  double rate_;
  long samples_ = 0;
  double prior_scale_ = 1;  // forget()s before the first sample
};

}  // namespace planner
