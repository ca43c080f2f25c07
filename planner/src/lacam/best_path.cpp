#include "planner/lacam/best_path.hpp"

#include <algorithm>

namespace planner {

void BestPath::reset(const Config& goals)
{
  goals_ = goals;
  n_ = static_cast<int>(goals.size());
  nodes_.clear();
  last_.assign(n_, -1);
  cost_ = 0;
  wait_.assign(n_, 0);
  cand_.clear();
  pricing_ = false;
  ++version_;
}

int64_t BestPath::price(const std::vector<int32_t>& last) const
{
  int64_t c = 0;
  for (int i = 0; i < n_; ++i)
    if (last[i] >= 0) c += last[i] + 1 + wait_[i];
  return c;
}

bool BestPath::advance(const HNode* from, HNode* to, bool carry)
{
  for (int i = 0; i < n_; ++i) wait_[i] = from->C[i] == goals_[i] && to->C[i] == goals_[i] ? wait_[i] + 1 : 0;
  if (nodes_.size() >= 2 && nodes_[1] == to) {
    nodes_.erase(nodes_.begin());
    for (int i = 0; i < n_; ++i) last_[i] = std::max(-1, last_[i] - 1);
    cost_ = price(last_);
  } else if (!nodes_.empty() && nodes_[0] != to) {
    nodes_.clear();
    ++version_;
  }
  if (pricing_) {
    if (cand_.size() >= 2 && cand_[1] == to) {
      cand_.erase(cand_.begin());
      scanned_ = std::min(scanned_, cand_.size());
    } else if (carry && !cand_.empty() && cand_[0] == from) {
      cand_.insert(cand_.begin(), to);
      return true;
    } else if (cand_.empty() || cand_[0] != to) {
      pricing_ = false;
    }
  }
  return false;
}

void BestPath::start_candidate(std::vector<HNode*> p)
{
  cand_ = std::move(p);
  cand_end_.assign(n_, -1);
  scanned_ = 0;
  pricing_ = !cand_.empty();
}

bool BestPath::price_node()
{
  if (!pricing_) return true;
  if (scanned_ < cand_.size()) {
    const int32_t d = static_cast<int32_t>(scanned_);
    const Vertex* C = cand_[cand_.size() - 1 - scanned_]->C;
    for (int i = 0; i < n_; ++i)
      if (cand_end_[i] < 0 && C[i] != goals_[i]) cand_end_[i] = d;
    if (++scanned_ < cand_.size()) return false;
  }
  pricing_ = false;
  const int32_t T = static_cast<int32_t>(cand_.size()) - 1;
  std::vector<int32_t> last(n_);
  for (int i = 0; i < n_; ++i) last[i] = cand_end_[i] < 0 ? -1 : std::max(-1, T - cand_end_[i]);
  const int64_t c = price(last);
  if (nodes_.empty() || c < cost_) {
    nodes_.swap(cand_);
    last_.swap(last);
    cost_ = c;
    ++version_;
  }
  cand_.clear();
  return true;
}

bool BestPath::splice(const HNode* from, const std::vector<HNode*>& window, const std::vector<int>& agents)
{
  if (window.empty()) return false;
  const auto at = std::find(nodes_.begin(), nodes_.end(), from);
  if (at == nodes_.end()) return false;
  const size_t k = static_cast<size_t>(at - nodes_.begin()), W = window.size();
  if (k + W >= nodes_.size() || nodes_[k + W] != window.back()) return false;
  std::vector<HNode*> p = nodes_;
  std::copy(window.begin(), window.end(), p.begin() + static_cast<std::ptrdiff_t>(k + 1));
  std::vector<int32_t> last = last_;
  const int32_t end = static_cast<int32_t>(k + W);
  for (int i : agents) {
    if (last[i] > end) continue;  // leaves its goal after the window: unchanged
    last[i] = -1;
    for (int32_t t = end; t >= 0; --t)
      if (p[t]->C[i] != goals_[i]) {
        last[i] = t;
        break;
      }
  }
  const int64_t c = price(last);
  if (c > cost_) return false;  // equal: LNS lowered the loss at the same SOC
  nodes_.swap(p);
  last_.swap(last);
  cost_ = c;
  ++version_;
  return true;
}

}  // namespace planner
