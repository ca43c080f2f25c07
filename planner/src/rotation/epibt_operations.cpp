// Epibt's operation set (epibt.hpp): the paper's sequences of actions, pruned, one per
// signature (cells visited, final heading), each with its tail ("RFF" -> "FFW"), and the
// options that pick its depth.
#include "planner/rotation/epibt.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

namespace planner {

namespace {

constexpr char kActs[4] = {'F', 'R', 'C', 'W'};

// The paper's weight of an operation (rotation model): forward early counts most; waits
// and turns early cost a little. Only orders operations whose costs tie.
int weight(const std::string& a)
{
  const int n = static_cast<int>(a.size());
  int w = 0;
  for (int d = 0; d < n; ++d) {
    if (a[d] == 'F') w += (n - d + 1) * 10;
    else if (a[d] == 'W') w -= (n - d) * 3;
    else w -= (n - d) * 2;
  }
  return w;
}

// The paper's pruning: no turn after the last forward (the end state's h sees the heading
// anyway), no R and C without a forward between (undone), no three equal turns without one.
bool useful(const std::string& a)
{
  const int n = static_cast<int>(a.size());
  for (int d = n - 1; d >= 0 && a[d] != 'F'; --d)
    if (a[d] != 'W') return false;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n && a[j] != 'F'; ++j) {
      if ((a[i] == 'R' && a[j] == 'C') || (a[i] == 'C' && a[j] == 'R')) return false;
      for (int k = j + 1; k < n && a[k] != 'F'; ++k)
        if (a[i] != 'W' && a[i] == a[j] && a[j] == a[k]) return false;
    }
  return true;
}

// Cells (relative to a robot at (0, 0) facing east) after each action, and the final heading:
// operations with one signature occupy the same cells at the same times.
std::vector<int> signature(const std::string& a)
{
  int x = 0, y = 0, o = 0;
  std::vector<int> s;
  for (char c : a) {
    if (c == 'F') x += kHeadingDx[o], y += kHeadingDy[o];
    o = heading_after(o, c);
    s.push_back(x), s.push_back(y);
  }
  s.push_back(o);
  return s;
}

}  // namespace

std::vector<std::string> Epibt::operations(int depth)
{
  // Below 3 the pruned set has no half turn ("RRF"): a robot facing a dead end's wall is stuck.
  if (depth < 3 || depth > 5) throw std::invalid_argument("epibt: operation depth must be 3..5");
  std::vector<std::string> all;
  int total = 1;
  for (int d = 0; d < depth; ++d) total *= 4;
  for (int code = 0; code < total; ++code) {
    std::string a;
    for (int d = 0, c = code; d < depth; ++d, c /= 4) a.insert(a.begin(), kActs[c % 4]);
    if (useful(a)) all.push_back(a);
  }
  // One per signature: the one that acts earliest (highest weight; "RWF" before "WRF": a
  // robot that turns now can go on if the cell clears sooner). Best first, WWW last.
  std::stable_sort(all.begin(), all.end(), [](const std::string& x, const std::string& y) { return weight(x) > weight(y); });
  std::map<std::vector<int>, bool> seen;
  std::vector<std::string> out;
  for (const std::string& a : all)
    if (seen.emplace(signature(a), true).second) out.push_back(a);
  return out;
}

void Epibt::set_options(const Options& opt)
{
  if (opt.revisit < 1 || opt.lns_revisit < 1) throw std::invalid_argument("epibt: revisit and lns_revisit must be >= 1");
  const std::vector<std::string> names = operations(opt.depth);
  opt_ = opt;
  ops_.clear();
  std::map<std::vector<int>, int> by_sig;
  for (size_t k = 0; k < names.size(); ++k) {
    ops_.push_back({names[k], -1});
    by_sig[signature(names[k])] = static_cast<int>(k);
    if (names[k] == std::string(static_cast<size_t>(opt_.depth), 'W')) wait_ = static_cast<int>(k);
  }
  for (Op& op : ops_) {  // the tail plus a wait has the signature of a kept operation
    const std::string tail = op.acts.substr(1) + "W";
    op.next = by_sig.at(signature(tail));
  }
  // Every robot waits: jointly conflict-free whatever they held before.
  const size_t n = current_.size(), D = static_cast<size_t>(opt_.depth);
  used_cell_.assign(static_cast<size_t>(g_.size()) * D, -1);
  used_edge_.assign(static_cast<size_t>(g_.size()) * 2 * D, -1);
  op_.assign(n, wait_);
  cells_.assign(n * D, -1);
  edges_.assign(n * D, -1);
  for (size_t i = 0; i < n; ++i) set_op(static_cast<int>(i), wait_), place(static_cast<int>(i));
  cand_.assign(n * ops_.size(), 0);
  score_of_.assign(n * ops_.size(), 0);
  power_.assign(n, 0.0);
  rng_ = Rng(opt.seed);
  ++stamp_;  // candidates of the old set are stale
  planned_ = false;
  tf_reset();
}

}  // namespace planner
