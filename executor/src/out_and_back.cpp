#include "executor/out_and_back.hpp"

#include <stdexcept>

namespace executor {

void OutAndBack::push(const planner::Config& c)
{
  if (c.size() != tail_.size()) throw std::invalid_argument("OutAndBack::push: configuration of the wrong size");
  buf_.push_back(c);
  // A cut frees v and may complete another agent's out-and-back (one that waits for v no
  // longer does): repeat until nothing changes. Each cut removes two moves, so this ends.
  for (bool more = true; more;) {
    more = false;
    for (size_t e = 2; e <= buf_.size(); ++e)
      for (int i = 0; i < static_cast<int>(c.size()); ++i) more = cut(i, e) || more;
  }
}

bool OutAndBack::cut(int i, size_t e)
{
  // Positions k = 0 (tail) .. size(): the agent is back on u at e after a stay on v over
  // [s, e - 1], and was on u at s - 1; only held configurations (k >= 1) may change.
  const planner::Vertex u = at(e)[i], v = at(e - 1)[i];
  if (u == v) return false;
  size_t s = e - 1;
  if (loops_) {
    // The agent's last stay on u before e: it is off u over [s, e - 1].
    while (s >= 1 && at(s - 1)[i] != u) --s;
  } else {
    while (s >= 1 && at(s - 1)[i] == v) --s;
  }
  if (s < 1 || at(s - 1)[i] != u) return false;
  for (size_t k = s; k < e; ++k) {
    if (limits_.keep && limits_.keep(i, at(k)[i])) return false;  // a visit that must stay
    for (size_t j = 0; j < at(k).size(); ++j) {
      if (static_cast<int>(j) == i) continue;
      if (at(k)[j] == u) return false;  // someone else uses u meanwhile
      if (limits_.exclusive && limits_.exclusive(u, at(k)[j])) return false;  // or u's zone
    }
  }
  for (size_t k = s; k < e; ++k) buf_[k - 1][i] = u;
  ++cuts_;
  return true;
}

planner::Config OutAndBack::pop()
{
  if (buf_.empty()) throw std::logic_error("OutAndBack::pop: nothing held");
  tail_ = buf_.front();
  buf_.pop_front();
  return tail_;
}

}  // namespace executor
