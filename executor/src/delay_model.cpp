#include "executor/delay_model.hpp"

#include <cmath>

namespace executor {

std::string check(const DelaySpec& s, int n)
{
  if (s.kind != "none" && s.kind != "bernoulli" && s.kind != "poisson")
    return "kind: '" + s.kind + "' is not none, bernoulli or poisson";
  if (!(s.p >= 0 && s.p <= 1)) return "p: " + std::to_string(s.p) + " is not in [0, 1]";
  if (!(s.rate >= 0) || !std::isfinite(s.rate)) return "rate: " + std::to_string(s.rate) + " is not >= 0";
  if (s.min_ticks < 1 || s.max_ticks < s.min_ticks)
    return "duration: [" + std::to_string(s.min_ticks) + ", " + std::to_string(s.max_ticks) +
           "] ticks is not a range 1 <= min <= max";
  if (!(s.fraction > 0 && s.fraction <= 1)) return "fraction: " + std::to_string(s.fraction) + " is not in (0, 1]";
  for (const Slowdown& d : s.slow) {
    if (d.agent < 0 || d.agent >= n) return "slow: agent " + std::to_string(d.agent) + " is not in [0, " + std::to_string(n) + ")";
    if (!(d.factor > 0 && d.factor <= 1)) return "slow: factor " + std::to_string(d.factor) + " is not in (0, 1]";
  }
  for (const Stuck& d : s.stuck) {
    if (d.agent < 0 || d.agent >= n) return "stuck: agent " + std::to_string(d.agent) + " is not in [0, " + std::to_string(n) + ")";
    if (d.at < 0 || d.ticks < 1) return "stuck: needs at >= 0 and a duration >= 1 tick";
  }
  return "";
}

DelayModel::DelayModel(const DelaySpec& s, int n)
    : s_(s), rng_(s.seed ^ 0xD1B54A32D192ED03ull), left_(n, 0), factor_(n, 1.0), eligible_(n, 1)
{
  for (const Slowdown& d : s.slow) factor_[d.agent] = d.factor;
  if (s.fraction < 1)
    for (int i = 0; i < n; ++i) eligible_[i] = rng_.uniform() < s.fraction;
  if (s.kind == "bernoulli") p_start_ = s.p;
  if (s.kind == "poisson") p_start_ = 1 - std::exp(-s.rate);
}

int DelayModel::move_ticks(int agent) const
{
  return static_cast<int>(std::ceil(1.0 / factor_[agent] - 1e-9));
}

void DelayModel::tick(long long t)
{
  const int n = static_cast<int>(left_.size());
  for (int i = 0; i < n; ++i) {
    if (left_[i] > 0) --left_[i];  // the previous tick's stop is one tick shorter
    // Draw for every agent every tick so one agent's stops do not shift the others'.
    const float u = rng_.uniform();
    const uint32_t len = rng_.below(static_cast<uint32_t>(s_.max_ticks - s_.min_ticks + 1));
    if (left_[i] == 0 && eligible_[i] && p_start_ > 0 && u < p_start_) {
      left_[i] = s_.min_ticks + len;
      ++stops_;
    }
  }
  for (const Stuck& d : s_.stuck)
    if (t == d.at && d.ticks > left_[d.agent]) {
      left_[d.agent] = d.ticks;
      ++stops_;
    }
  for (int i = 0; i < n; ++i) stop_ticks_ += left_[i] > 0;
}

}  // namespace executor
