#include "planner/lacam/lns_refiner.hpp"

#include <algorithm>
#include <cstdlib>
#include <queue>
#include <stdexcept>

namespace planner {

int64_t LnsRefiner::agent_cost(const std::vector<Config>& path, const Config& goals, int i, int t0, int t1)
{
  int64_t c = 0;
  for (int t = t0; t < t1; ++t) c += !(path[t][i] == goals[i] && path[t + 1][i] == goals[i]);
  return c;
}

int64_t LnsRefiner::agent_moves(const std::vector<Config>& path, int i, int t0, int t1)
{
  int64_t c = 0;
  for (int t = t0; t < t1; ++t) c += path[t + 1][i] != path[t][i];
  return c;
}

int64_t LnsRefiner::agent_stops(const std::vector<Config>& path, int i, int t0, int t1)
{
  int64_t c = 0;
  for (int t = t0 + 1; t < t1; ++t) {
    const Vertex a = path[t - 1][i], v = path[t][i], u = path[t + 1][i];
    c += u != v && (a == v || a == u);
  }
  return c;
}

int64_t LnsRefiner::agent_soc(const std::vector<Config>& path, const Config& goals, int i, int t0, int t1, bool stays)
{
  if (!stays) return t1 - t0;
  for (int t = t1; t >= t0; --t)
    if (path[t][i] != goals[i]) return t - t0 + 1;  // last off the goal; arrives at t + 1
  return 0;
}

int64_t LnsRefiner::cost_of(const std::vector<Config>& path, const Config& goals, int i, int t0, int t1,
                            const uint8_t* stays) const
{
  if (obj_ == Objective::loss) return agent_cost(path, goals, i, t0, t1);
  return agent_soc(path, goals, i, t0, t1, stays ? stays[i] != 0 : path[t1][i] == goals[i]);
}

void LnsRefiner::reserve_tables()
{
  max_window_ = std::max(max_window_, window_);
  const size_t cells = static_cast<size_t>(max_window_ + 1) * g_.size();
  occ_.ensure(cells);
  // a stop cost doubles the A*'s states (stood or not); the second half is touched only then
  best_.ensure(stop_cost_ > 0 ? 2 * cells : cells);
  stamp_.ensure(stop_cost_ > 0 ? 2 * cells : cells);
  if (nbh_ == LnsNeighbourhood::blocking || nbh_ == LnsNeighbourhood::adaptive) at_.ensure(cells);
}

int LnsRefiner::warm_window() const
{
  return static_cast<int>(occ_.touched() / std::max<size_t>(g_.size(), 1)) - 1;
}

// Only the occupancy table: a step writes every agent's cell at every step of its window
// into it (N x W cells over all its pages), while the A*'s tables see a few pages per step.
bool LnsRefiner::warm(int window, Clock::time_point deadline)
{
  reserve_tables();
  const size_t want = static_cast<size_t>(std::min(window, max_window_) + 1) * g_.size();
  constexpr size_t kPiece = 16 * LazyTable<int32_t>::kPage / sizeof(int32_t);  // 16 pages per clock reading
  while (occ_.touched() < want) {
    occ_.touch(std::min(want, occ_.touched() + kPiece));
    if (occ_.touched() < want && Clock::now() >= deadline) return false;
  }
  return true;
}

// Space-time A* for agent i from (path[t0][i], t0) to (path[t1][i], t1) around the agents in
// occ_; cost per step 1, but 0 for waiting on the goal (loss; soc for an agent that leaves its
// goal after t1, whose standard SOC no path changes) or 1 throughout (soc, settling). h =
// |d(v, goal) - d(end, goal)|, a lower bound on d(v, end) from the goal's distance table (no
// table per window end). `settle` (soc; the end is the goal): done on reaching the goal once
// nobody else stands there until t1 (then it waits there), so the first such pop is the
// earliest arrival that is not pushed off again.
bool LnsRefiner::replan(int i, const std::vector<Config>& path, const Config& goals, int t0, int t1,
                        std::vector<Vertex>& out, Clock::time_point deadline, bool settle)
{
  const size_t V = g_.size();
  const Vertex goal = goals[i], end = path[t1][i];
  const int32_t d_end = dist_.get(i, end);
  // Flat window x |V| table of best g, valid where its stamp is this call's (no hashing, no
  // clearing, no allocation once grown: the step is real-time work).
  const size_t W = static_cast<size_t>(t1 - t0 + 1);  // tables: allocated for the largest window (reserve_tables)
  if (++epoch_ == 0) {  // wrapped: stale stamps could collide
    for (size_t k = 0; k < stamp_.size(); ++k) stamp_[k] = 0;
    epoch_ = 1;
  }
  nodes_.clear();
  open_ = {};
  // Stop cost: g = P x (the step cost) + c x (moves from rest); P = 1 where the step cost is
  // the loss (the secondary cost, which the stops join), and above any stop total where it is
  // the standard SOC (settle: it stays primary, so the stops only break its ties).
  const int64_t c_stop = stop_cost_;
  const bool moves = count_moves_ && obj_ == Objective::soc;  // secondary: moves, not the loss
  const int64_t P = (c_stop > 0 || moves) && settle ? (c_stop + 1) * static_cast<int64_t>(t1 - t0 + 1) + 1 : 1;
  auto h = [&](Vertex v) { return P * static_cast<int64_t>(std::abs(dist_.get(i, v) - d_end)); };
  auto slot = [&](int t, Vertex v) { return static_cast<size_t>(t - t0) * V + static_cast<size_t>(v); };
  const size_t half = best_.size() / 2;  // stood states' offset (stop cost only)
  auto key = [&](int t, Vertex v, bool stood) { return slot(t, v) + (stood ? half : 0); };
  const Vertex s = path[t0][i];
  nodes_.push_back({s, t0, 0, -1, false});
  best_[key(t0, s, false)] = 0;
  stamp_[key(t0, s, false)] = epoch_;
  open_.push({h(s), -t0, 0});
  int free_from = t1 + 1;  // settle: the goal is free of others from here to t1
  if (settle) {
    free_from = t1;
    while (free_from > t0 && occ_[slot(free_from - 1, goal)] == 0) --free_from;
  }
  // Bound the work of one replan: a failing search would otherwise sweep |V| x window states.
  const size_t limit = 32 * W + 1024;
  size_t pops = 0;
  bool found = false;
  if (Clock::now() >= deadline) return false;
  while (!open_.empty() && nodes_.size() < limit) {
    // Counted over the step's replans: one failing search of a short window has fewer pops
    // than the check interval, and eight of them overran a 1 ms iteration by 0.5 ms.
    if ((++clock_pops_ & 63) == 0 && Clock::now() >= deadline) break;
    ++pops;
    auto [f, negt, idx] = open_.top();
    open_.pop();
    const AstarNode n = nodes_[idx];
    if (best_[key(n.t, n.v, n.stood)] < n.g) continue;
    if (n.t == t1 || (settle && n.v == goal && n.t >= free_from)) {
      if (n.v != end) continue;
      out.assign(W, goal);  // settle: waits on the goal after arriving
      for (int32_t k = idx; k >= 0; k = nodes_[k].parent) out[nodes_[k].t - t0] = nodes_[k].v;
      found = true;
      break;
    }
    if (P * (t1 - n.t) < h(n.v)) continue;  // cannot reach the end in time
    const Vertex came = n.parent >= 0 ? nodes_[n.parent].v : n.v;  // came == v: stood (or no history)
    const auto nb = g_.neighbors(n.v);
    for (size_t m = 0; m <= nb.size(); ++m) {
      const Vertex u = m < nb.size() ? nb[m] : n.v;
      const size_t at = slot(n.t + 1, u);
      if (occ_[at] != 0) continue;  // vertex conflict
      if (u != n.v) {
        const int32_t j = occ_[slot(n.t, u)];
        if (j != 0 && occ_[slot(n.t + 1, n.v)] == j) continue;  // swap conflict
      }
      int64_t g = n.g + (settle ? P + (moves && u != n.v) : moves ? (u != n.v) : !(n.v == goal && u == goal));
      bool stood = false;
      if (c_stop > 0) {
        stood = u == n.v;
        if (u != n.v && n.parent >= 0 && (n.stood || came == u)) g += c_stop;  // a move from rest
      }
      const size_t k = key(n.t + 1, u, stood);
      if (stamp_[k] == epoch_ && best_[k] <= g) continue;
      stamp_[k] = epoch_;
      best_[k] = static_cast<int32_t>(g);
      nodes_.push_back({u, n.t + 1, g, idx, stood});
      open_.push({g + h(u), -(n.t + 1), static_cast<int32_t>(nodes_.size() - 1)});
    }
  }
  work_ += nodes_.size() + pops;
  return found;
}

LnsNeighbourhood parse_lns_neighbourhood(const std::string& s)
{
  if (s == "random") return LnsNeighbourhood::random;
  if (s == "blocking") return LnsNeighbourhood::blocking;
  if (s == "intersection") return LnsNeighbourhood::intersection;
  if (s == "adaptive") return LnsNeighbourhood::adaptive;
  throw std::invalid_argument("unknown LNS neighbourhood '" + s + "' (random | blocking | intersection | adaptive)");
}

void LnsRefiner::neighbourhood(int h, const std::vector<Config>& path, const Config& goals,
                               const std::vector<int64_t>& cost, int k, int t0, int t1, Rng& rng)
{
  const int n = static_cast<int>(goals.size());
  const size_t V = g_.size();
  auto in = [&](int j) { return std::find(set_.begin(), set_.end(), j) != set_.end(); };
  std::vector<int> cand;
  if (h == 1) {  // blocking chains, breadth-first from the seed
    const size_t W = static_cast<size_t>(t1 - t0 + 1);
    at_.ensure(W * V);  // allocated for the largest window already (reserve_tables)
    for (int t = t0; t <= t1; ++t)
      for (int i = 0; i < n; ++i) at_[static_cast<size_t>(t - t0) * V + static_cast<size_t>(path[t][i])] = i + 1;
    work_ += W * static_cast<size_t>(n);
    for (size_t q = 0; q < set_.size() && static_cast<int>(set_.size()) < k; ++q) {
      const int a = set_[q];
      cand.clear();
      for (int t = t0; t < t1; ++t) {
        const Vertex v = path[t][a];
        if (v == goals[a] || dist_.get(a, path[t + 1][a]) < dist_.get(a, v)) continue;  // progress
        for (Vertex u : g_.neighbors(v)) {
          if (dist_.get(a, u) >= dist_.get(a, v)) continue;
          const int32_t j = at_[static_cast<size_t>(t + 1 - t0) * V + static_cast<size_t>(u)] - 1;
          if (j >= 0 && j != a && !in(j) &&
              std::find(cand.begin(), cand.end(), j) == cand.end())
            cand.push_back(j);
        }
      }
      work_ += static_cast<uint64_t>(t1 - t0);
      rng.shuffle(cand.data(), static_cast<int>(cand.size()));
      for (int j : cand)
        if (static_cast<int>(set_.size()) < k) set_.push_back(j);
    }
    // at_ is rewritten before every use, but stale agents must not answer: clear what was set
    for (int t = t0; t <= t1; ++t)
      for (int i = 0; i < n; ++i) at_[static_cast<size_t>(t - t0) * V + static_cast<size_t>(path[t][i])] = 0;
  } else if (h == 2) {  // the agents crossing one intersection of the seed's path
    const int a = set_[0];
    std::vector<Vertex> cross;
    for (int t = t0; t <= t1; ++t)
      if (g_.neighbors(path[t][a]).size() >= 3) cross.push_back(path[t][a]);
    if (cross.empty()) cross.push_back(path[t0 + static_cast<int>(rng.below(static_cast<uint32_t>(t1 - t0 + 1)))][a]);
    const Vertex x = cross[rng.below(static_cast<uint32_t>(cross.size()))];
    for (int i = 0; i < n; ++i) {
      if (i == a) continue;
      for (int t = t0; t <= t1; ++t)
        if (path[t][i] == x) {
          cand.push_back(i);
          break;
        }
    }
    work_ += static_cast<uint64_t>(t1 - t0 + 1) * static_cast<uint64_t>(n);
    rng.shuffle(cand.data(), static_cast<int>(cand.size()));
    for (int j : cand)
      if (static_cast<int>(set_.size()) < k) set_.push_back(j);
  }
  (void)cost;
  // Too few (or random): random others fill the set (MAPF-LNS does the same).
  for (int tries = 0; static_cast<int>(set_.size()) < k && tries < 4 * k; ++tries) {
    const int j = static_cast<int>(rng.below(static_cast<uint32_t>(n)));
    if (!in(j)) set_.push_back(j);
  }
}

bool LnsRefiner::step(std::vector<Config>& path, const Config& goals, int k, Rng& rng, Clock::time_point deadline,
                      const uint8_t* stays, int seed)
{
  const int n = static_cast<int>(goals.size());
  const int T = static_cast<int>(path.size()) - 1;
  work_ = static_cast<uint64_t>(T + 1) * static_cast<uint64_t>(n);  // the cost pass below
  if (T < 1 || n == 0) return false;
  reserve_tables();
  // A delayed agent seeds the neighbourhood: only where someone waits or detours can the
  // cost drop. One pass in time order (the configurations are stored by time step).
  const bool soc = obj_ == Objective::soc;
  auto stays_after = [&](int i) { return stays ? stays[i] != 0 : path[T][i] == goals[i]; };
  std::vector<int64_t> cost(n, 0);
  std::vector<int32_t> last(soc ? n : 0, -1);
  if (soc) {  // the last step off the goal, per agent
    for (int t = 0; t < T; ++t)
      for (int i = 0; i < n; ++i)
        if (path[t][i] != goals[i]) last[i] = t;
    for (int i = 0; i < n; ++i) cost[i] = stays_after(i) ? last[i] + 1 : T;
  } else {
    for (int t = 0; t < T; ++t)
      for (int i = 0; i < n; ++i) cost[i] += !(path[t][i] == goals[i] && path[t + 1][i] == goals[i]);
  }
  // The seed: a delayed agent, roulette by delay over what the path's ends allow (a window of
  // a longer path need not end at the goals). Under soc only an agent that stays on its goal
  // after the window can gain: one that leaves later costs the whole window anyway.
  std::vector<int64_t> delay(n, 0);
  int64_t total_delay = 0;
  for (int i = 0; i < n; ++i) {
    if (soc && !stays_after(i)) continue;
    delay[i] = std::max<int64_t>(0, cost[i] - std::abs(dist_.get(i, path[0][i]) - dist_.get(i, path[T][i])));
    total_delay += delay[i];
  }
  if (seed >= 0 && seed < n) total_delay = std::max<int64_t>(total_delay, 1);  // the caller's seed
  if (total_delay <= 0) return false;
  // The time window [t0, t1]: the agents keep their positions at both ends.
  const int t0 = T > window_ ? static_cast<int>(rng.below(static_cast<uint32_t>(T - window_ + 1))) : 0;
  const int t1 = std::min(T, t0 + window_);
  // soc: who stays on the goal after t1 (after the path's end, and from t1 to it)
  std::vector<uint8_t> settled(soc ? n : 0, 0);
  for (int i = 0; soc && i < n; ++i) settled[i] = stays_after(i) && last[i] < t1 && path[t1][i] == goals[i];
  const uint8_t* st = soc ? settled.data() : nullptr;
  int h = static_cast<int>(nbh_);
  if (nbh_ == LnsNeighbourhood::adaptive) {
    const double r = rng.uniform() * (weight_[0] + weight_[1] + weight_[2]);
    h = r < weight_[0] ? 0 : r < weight_[0] + weight_[1] ? 1 : 2;
  }
  last_h_ = h;
  set_.clear();
  int64_t r = static_cast<int64_t>(rng.uniform() * static_cast<double>(total_delay));
  if (seed >= 0 && seed < n) set_.push_back(seed);
  for (int i = 0; i < n && set_.empty(); ++i) {
    r -= delay[i];
    if (r < 0 || i == n - 1) {
      set_.push_back(i);
      break;
    }
  }
  if (soc) {  // who passes the seed's goal: they push it off, or keep it from arriving
    const int a = set_[0];
    std::vector<int> cand;
    for (int t = t0; t <= t1; ++t)
      for (int j = 0; j < n; ++j)
        if (j != a && path[t][j] == goals[a] && std::find(cand.begin(), cand.end(), j) == cand.end()) cand.push_back(j);
    work_ += static_cast<uint64_t>(t1 - t0 + 1) * static_cast<uint64_t>(n);
    rng.shuffle(cand.data(), static_cast<int>(cand.size()));
    for (int j : cand)
      if (static_cast<int>(set_.size()) < std::min(k, n)) set_.push_back(j);
  }
  neighbourhood(h, path, goals, cost, std::min(k, n), t0, t1, rng);
  std::vector<int>& set = set_;

  const size_t V = g_.size();
  written_.clear();
  std::vector<char> in_set(n, 0);
  for (int i : set) in_set[i] = 1;
  for (int t = t0; t <= t1; ++t)
    for (int i = 0; i < n; ++i)
      if (!in_set[i]) {
        const size_t key = static_cast<size_t>(t - t0) * V + static_cast<size_t>(path[t][i]);
        occ_[key] = i + 1;
        written_.push_back(key);
      }

  work_ += written_.size();
  // Under soc the cost is (standard SOC, loss) lexicographically: soc x S + loss, S above any
  // loss of the set. A step that keeps the standard SOC and lowers the loss wins too: it frees
  // room (waits, detours of agents whose SOC is fixed by a later leave) for the next steps.
  // A stop cost c adds c per move from rest to the loss (secondary under soc): S grows with it.
  const int64_t S = soc ? (1 + stop_cost_) * static_cast<int64_t>(t1 - t0 + 1) * static_cast<int64_t>(set.size()) + 1 : 1;
  int64_t before = 0;
  for (int i : set) {
    before += cost_of(path, goals, i, t0, t1, st) * S;
    if (soc) before += count_moves_ ? agent_moves(path, i, t0, t1) : agent_cost(path, goals, i, t0, t1);
    if (stop_cost_ > 0) before += stop_cost_ * agent_stops(path, i, t0, t1);
  }
  rng.shuffle(set.data(), static_cast<int>(set.size()));
  std::vector<std::vector<Vertex>> fresh(set.size());
  int64_t after = 0;
  bool ok = true;
  for (size_t m = 0; m < set.size() && ok; ++m) {
    const int i = set[m];
    const bool settle = soc && settled[i];
    ok = replan(i, path, goals, t0, t1, fresh[m], deadline, settle);
    if (!ok) break;
    int last_off = -1;
    for (int t = t0; t <= t1; ++t) {
      const Vertex v = fresh[m][t - t0];
      const size_t key = static_cast<size_t>(t - t0) * V + static_cast<size_t>(v);
      occ_[key] = i + 1;
      written_.push_back(key);
      if (v != goals[i]) last_off = t;
      if (t < t1) after += soc && count_moves_ ? v != fresh[m][t - t0 + 1] : !(v == goals[i] && fresh[m][t - t0 + 1] == goals[i]);
    }
    if (soc) after += S * (settle ? (last_off < 0 ? 0 : last_off - t0 + 1) : t1 - t0);
    for (int t = t0 + 1; stop_cost_ > 0 && t < t1; ++t) {
      const Vertex a = fresh[m][t - 1 - t0], v = fresh[m][t - t0], u = fresh[m][t + 1 - t0];
      after += stop_cost_ * (u != v && (a == v || a == u));
    }
    if (after >= before) ok = false;  // cannot win any more
  }
  for (size_t key : written_) occ_[key] = 0;
  written_.clear();
  constexpr double kGamma = 0.01;  // MAPF-LNS's reaction factor
  const bool won = ok && after < before;
  if (nbh_ == LnsNeighbourhood::adaptive)
    weight_[h] = std::max(1e-3, (won ? kGamma * static_cast<double>(before - after) / static_cast<double>(S * set.size()) : 0.0) +
                                    (1 - kGamma) * weight_[h]);
  if (!won) return false;
  for (size_t m = 0; m < set.size(); ++m)
    for (int t = t0; t <= t1; ++t) path[t][set[m]] = fresh[m][t - t0];
  return true;
}

}  // namespace planner
