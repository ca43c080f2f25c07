#include "controller/expansion_reserve.hpp"

#include <algorithm>

namespace controller {

ExpansionReserve::ExpansionReserve(size_t window, double max_share)
    : window_(std::max<size_t>(window, 1)), max_share_(max_share)
{
}

void ExpansionReserve::record(double search_cpu_ms, uint64_t expansions)
{
  if (expansions == 0 || !(search_cpu_ms >= 0)) return;
  const double c = search_cpu_ms / static_cast<double>(expansions);
  if (per_expansion_.size() < window_) {
    per_expansion_.push_back(c);
  } else {
    per_expansion_[next_] = c;
    next_ = (next_ + 1) % window_;
  }
}

double ExpansionReserve::ms(double budget_ms) const
{
  if (per_expansion_.empty() || !(budget_ms > 0)) return 0;
  const double dearest = *std::max_element(per_expansion_.begin(), per_expansion_.end());
  return std::min(dearest, max_share_ * budget_ms);
}

}  // namespace controller
