#include "planner/lacam/pibt.hpp"

#include <algorithm>

namespace planner {

Pibt::Pibt(const Graph& g, DistTable& d, bool swap)
    : g_(g), d_(d), swap_(swap), stride_(g.max_degree() + 1), occ_now_(g.size(), -1), occ_next_(g.size(), -1),
      key_(stride_), detour_(g, &d)
{
}

void Pibt::set_goals(const Config& goals)
{
  // Forget the marks of the previous generate() before the agent arrays change size.
  for (int i = 0; i < n_; ++i) {
    if (now_[i] >= 0) occ_now_[now_[i]] = -1;
    if (next_[i] >= 0) occ_next_[next_[i]] = -1;
  }
  pending_ = false;
  goals_ = goals;
  if (pref_) pref_->set_goals(goals);
  n_ = static_cast<int>(goals.size());
  now_.assign(n_, -1);
  next_.assign(n_, -1);
  cand_.assign(static_cast<size_t>(n_) * stride_, -1);
}

bool Pibt::generate(const Vertex* from, const int32_t* order, const Constraint* c, Vertex* to, Rng& rng)
{
  start(from, order, c);
  if (resume(rng) != Gen::done) return false;
  std::copy(next_.begin(), next_.end(), to);
  return true;
}

void Pibt::start(const Vertex* from, const int32_t* order, const Constraint* c)
{
  from_ = from;
  order_ = order;
  chain_ = c;
  phase_ = Phase::undo;
  k_ = 0;
  pending_ = true;
  lg_ = lg_next_;
}

// Every phase is a loop over agents (or constraints) with a cursor kept in members, so that
// it can stop between two of them. The clock is read every `every` units of this call.
Pibt::Gen Pibt::resume(Rng& rng, Clock::time_point deadline)
{
  const bool timed = deadline != Clock::time_point::max();
  int units = 0;  // of this call: the first every - 1 are always done
  auto stop = [&](int every) { return timed && ++units % every == 0 && Clock::now() >= deadline; };
  const Vertex* from = from_;
  if (phase_ == Phase::undo) {
    // Undo the previous call's reservations: O(N), no O(V) clearing.
    for (; k_ < n_; ++k_) {
      if (stop(kSetupEvery)) return Gen::paused;
      const int i = k_;
      if (now_[i] >= 0 && occ_now_[now_[i]] == i) occ_now_[now_[i]] = -1;
      if (next_[i] >= 0) occ_next_[next_[i]] = -1;
    }
    phase_ = Phase::place, k_ = 0;
    if (zones_) {
      zone_holder_.assign(zones_->count, -1);
      if (evict_zone_.size() != static_cast<size_t>(n_)) evict_zone_.assign(n_, -1);
      if (exit_dist_.size() != static_cast<size_t>(g_.size())) exit_dist_.assign(g_.size(), 0);
    }
  }
  if (phase_ == Phase::place) {
    for (; k_ < n_; ++k_) {
      if (stop(kSetupEvery)) return Gen::paused;
      const int i = k_;
      now_[i] = from[i];
      next_[i] = -1;
      occ_now_[from[i]] = i;
      if (zones_)
        for (int z : zones_->of[from[i]]) zone_holder_[z] = i;
      // The candidates' distances, ahead of plan() (DistTable::prefetch).
      d_.prefetch(i, from[i]);
      for (Vertex u : g_.neighbors(from[i])) d_.prefetch(i, u);
      if (guide_)
        for (Vertex u : g_.neighbors(from[i])) guide_->prefetch(i, u);
    }
    // O(N) in one piece, but only with a preference or immobile agents.
    if (pref_) pref_->prepare(from, n_);
    if (!immobile_.empty()) {  // immobile agents never move: their cells are fixed obstacles
      std::vector<Vertex> blocked;
      for (int i = 0; i < n_; ++i)
        if (immobile_[i]) blocked.push_back(from[i]);
      detour_.set_blocked(std::move(blocked));
      if (cut_off_stamp_.size() != static_cast<size_t>(n_)) cut_off_stamp_.assign(n_, 0), cut_off_.assign(n_, 0);
      if (++generation_ == 0) std::fill(cut_off_stamp_.begin(), cut_off_stamp_.end(), 0), generation_ = 1;
    }
    phase_ = Phase::chain;
  }
  if (phase_ == Phase::chain) {
    // Agents fixed by the constraint chain; reject fixes that collide with each other.
    for (; chain_ && chain_->depth > 0; chain_ = chain_->parent) {
      if (stop(kSetupEvery)) return Gen::paused;
      const int32_t i = chain_->who;
      const Vertex v = chain_->where;
      const int32_t j = occ_now_[v];
      if (occ_next_[v] >= 0 || (j >= 0 && j != i && next_[j] == from[i]) ||  // vertex / swap conflict
          !zone_free(i, v)) {                                       // a zone someone else holds
        pending_ = false;
        return Gen::failed;
      }
      next_[i] = v;
      occ_next_[v] = i;
      zone_take(i, from[i], v, true);
    }
    phase_ = lg_ ? Phase::guide : Phase::plan, k_ = 0;
    if (lg_) lg_->begin(from, n_, goals_.data());
  }
  if (phase_ == Phase::guide) {
    // Windowed paths in priority order (local_guidance.hpp): one A* per agent (LG-LaCAM);
    // amortized, only for an agent without a path or with a stale one while the round's node
    // budget lasts, a kept path going back into the tables at its agent's turn.
    for (; k_ < n_; ++k_) {
      const int32_t i = order_[k_];
      if (lg_->planned(i) && (lg_->over() || (!lg_->stale(i) && !(lg_->repair() && lg_->blocked(i))))) {
        lg_->hold(i);
        continue;
      }
      if (lg_->over()) continue;
      if (stop(kGuideEvery)) return Gen::paused;
      lg_->plan(i);
    }
    phase_ = Phase::plan, k_ = 0;
  }
  for (; k_ < n_; ++k_) {
    if (stop(kCheckEvery)) return Gen::paused;
    const int32_t i = order_[k_];
    ++plans_;
    if (next_[i] < 0 && !plan(i, rng)) {
      pending_ = false;
      return Gen::failed;
    }
  }
  pending_ = false;
  return Gen::done;
}

bool Pibt::plan(int32_t i, Rng& rng)
{
  const Vertex v = now_[i];
  if (immobile(i)) {
    // Its one candidate is staying: it fails if v is reserved already (a pusher asking it
    // to move, or a constraint fixing someone there); either way v stays its own.
    const bool ok = occ_next_[v] < 0 || occ_next_[v] == i;
    occ_next_[v] = i;
    next_[i] = v;
    return ok;
  }
  const auto nb = g_.neighbors(v);
  const int K = static_cast<int>(nb.size());
  Vertex* C = cand_.data() + static_cast<size_t>(i) * stride_;

  // Candidates (neighbours + stay), sorted by score; insertion sort on <= 5 entries.
  for (int k = 0; k < K; ++k) C[k] = nb[k];
  C[K] = v;
  // free_first: among moves toward the goal at the same distance, a free vertex first (keys in
  // [d, d + 1/3)), then one whose agent j can step on elsewhere ([d + 1/3, d + 2/3)), then one
  // whose agent wants v itself (head-on: it cannot have v, so it is pushed back) or is parked
  // on its goal ([d + 2/3, d + 1)); the same random draws.
  const float here = free_first_ && !pref_ ? distance(i, v) : 0.0f;
  for (int k = 0; k <= K; ++k) {
    if (pref_) {
      key_[k] = pref_->score(i, v, C[k], rng);
      continue;
    }
    const float d = distance(i, C[k]) + extra_cost(v, C[k]) + pocket_cost(i, v, C[k]);
    if (free_first_ && d < here) {
      const int32_t j = occ_now_[C[k]];
      const float level = j < 0 ? 0.0f : d_.get(j, C[k]) == 0 || d_.get(j, v) < d_.get(j, C[k]) ? 2.0f : 1.0f;
      key_[k] = d + (level + rng.uniform()) / 3.0f;
    } else
      key_[k] = d + rng.uniform();
  }
  if (scatter_ && scatter_->ready()) {
    const Vertex s = scatter_->next(i, v);
    for (int k = 0; k <= K; ++k)
      if (C[k] == s) key_[k] = -1e30f;
  }
  if (lg_) {  // the first step of its windowed path first (before the scatter successor)
    const Vertex s = lg_->next(i);
    for (int k = 0; k <= K; ++k)
      if (C[k] == s) key_[k] = -2e30f;
  }
  if (zones_ && evict_zone_[i] >= 0) {  // asked to leave a zone (evict): out first, else toward a way out
    const int z = evict_zone_[i];
    for (int k = 0; k <= K; ++k)
      // Scaled, not offset: 1e20f + 1 == 1e20f + 3 in float, which ranked the cells by
      // neighbour order and swung an evicted agent back and forth inside the zone.
      if (zones_->in(C[k], z)) key_[k] = 1e20f * static_cast<float>(1 + exit_dist_[C[k]]);
  }
  for (int k = 1; k <= K; ++k) {
    const Vertex u = C[k];
    const float key = key_[k];
    int j = k;
    for (; j > 0 && key < key_[j - 1]; --j) C[j] = C[j - 1], key_[j] = key_[j - 1];
    C[j] = u, key_[j] = key;
  }

  const int32_t partner = swap_ ? swap_partner(i) : -1;
  if (partner >= 0) {
    std::reverse(C, C + K + 1);
    // Reversed, a foreign pocket (pocket_cost) would come first: keep it the last resort, or
    // swaps drive agents into other stations' stubs (rtlacam on huge_warehouse_lifelong:
    // 0.53x errands with pocket_cost 100, s35).
    if (pocket_cost_ > 0.0f && !pocket_.empty())
      std::stable_partition(C, C + K + 1, [&](Vertex u) { return pocket_cost(i, v, u) == 0.0f; });
  }

  for (int k = 0; k <= K; ++k) {
    const Vertex u = C[k];
    if (occ_next_[u] >= 0) continue;               // vertex conflict
    const int32_t j = occ_now_[u];
    if (j >= 0 && next_[j] == v) continue;          // swap conflict
    if (!zone_free(i, u)) {                      // a zone someone else holds this step
      evict(i, v, u, rng);
      continue;
    }
    occ_next_[u] = i;
    next_[i] = u;
    zone_take(i, v, u, true);
    // Priority inheritance: j must make room; on failure j stays at u and u is j's.
    if (j >= 0 && j != i && next_[j] < 0 && !plan(j, rng)) {
      zone_take(i, v, u, false);
      continue;
    }
    // Swap: pull the partner into the vertex i is leaving.
    if (k == 0 && partner >= 0 && next_[partner] < 0 && occ_next_[v] < 0 && zone_free(partner, v)) {
      next_[partner] = v;
      occ_next_[v] = partner;
      zone_take(partner, now_[partner], v, true);
    }
    return true;
  }
  occ_next_[v] = i;
  next_[i] = v;
  return false;
}

void Pibt::evict(int32_t i, Vertex v, Vertex u, Rng& rng)
{
  for (int z : zones_->of[u]) {
    const int32_t j = zone_holder_[z];
    if (j < 0 || j == i || next_[j] >= 0 || immobile(j) || !zones_->in(now_[j], z)) continue;
    // Moves to a way out of z other than i's vertex: a BFS backwards from the vertices
    // outside z next to it (v excluded) over z's vertices.
    const std::vector<Vertex>& cells = zones_->cells[z];
    std::vector<Vertex> queue;
    for (Vertex c : cells) {
      exit_dist_[c] = 1 << 20;
      for (Vertex w : g_.neighbors(c))
        if (w != v && !zones_->in(w, z)) {
          exit_dist_[c] = 1;
          queue.push_back(c);
          break;
        }
    }
    for (size_t h = 0; h < queue.size(); ++h)
      for (Vertex c : cells)
        if (exit_dist_[c] > exit_dist_[queue[h]] + 1 && g_.adjacent(c, queue[h]))
          exit_dist_[c] = exit_dist_[queue[h]] + 1, queue.push_back(c);
    // i stays meanwhile (j's chain must not push it: it is being planned), unless someone
    // has v already (then nobody can enter v anyway).
    const bool hold = occ_next_[v] < 0;
    if (hold) occ_next_[v] = i, next_[i] = v;
    evict_zone_[j] = z;
    plan(j, rng);
    evict_zone_[j] = -1;
    if (hold) occ_next_[v] = -1, next_[i] = -1;
  }
}

float Pibt::distance(int32_t i, Vertex u)
{
  if (!detour_.active()) return static_cast<float>(guide_ ? guide_->get(i, u) : d_.get(i, u));
  DistCache::Table* t = d_.table(i);
  // Cut off from its goal by the immobile agents: plain distances (once per agent and call).
  if (cut_off_stamp_[i] != generation_) {
    cut_off_stamp_[i] = generation_;
    cut_off_[i] = detour_.get(goals_[i], now_[i], t) >= DistTable::kInf;
  }
  if (cut_off_[i]) return static_cast<float>(d_.get(i, u));
  return static_cast<float>(detour_.get(goals_[i], u, t));
}

bool Pibt::pull_impossible(Vertex u, Vertex v_pusher) const
{
  if (u == v_pusher) return true;
  const int32_t a = occ_now_[u];
  if (a >= 0 && immobile(a)) return true;  // a wall while it is immobile
  return g_.degree(u) == 1 && a >= 0 && goals_[a] == u;  // parked on its goal in a dead end
}

int32_t Pibt::swap_partner(int32_t i) const
{
  const Vertex v = now_[i];
  const Vertex best = cand_[static_cast<size_t>(i) * stride_];
  if (best == v) return -1;  // i wants to stay

  // The partner is pulled into v (plan()): on a directed graph only over an arc into v.
  auto can_pull = [&](int32_t k) { return !g_.directed() || g_.adjacent(now_[k], v); };

  // i is blocked by j coming the other way (cases a and b of LaCAM*).
  const int32_t j = occ_now_[best];
  if (j >= 0 && next_[j] < 0 && !immobile(j) && can_pull(j) && swap_required(i, j, v, best) && swap_possible(best, v))
    return j;

  // i clears the way for a neighbour k behind it (case c).
  for (Vertex u : g_.neighbors(v)) {
    const int32_t k = occ_now_[u];
    if (k < 0 || best == now_[k] || immobile(k) || !can_pull(k)) continue;
    if (swap_required(k, i, v, best) && swap_possible(best, v)) return k;
  }
  return -1;
}

// Simulates the pusher walking towards its goal through a corridor: the swap is required
// when the corridor never widens enough to let the two pass.
bool Pibt::swap_required(int32_t pusher, int32_t puller, Vertex v_pusher, Vertex v_puller) const
{
  // The ranking distances (highways): a swap decided on other distances than the ranking
  // that picked the pusher's move disagreed with it, and PIBT then pushed agents back and
  // forth (large SUMO warehouse, 200 AGVs: one AGV short of its goal for 6000 ticks).
  // Around immobile agents the ranking is the detour distance, which is built on the plain
  // ones: the swap reads those there, as it did before highways.
  DistTable& d = guide_ && !detour_.active() ? *guide_ : d_;
  Vertex tmp = -1;
  while (d.get(pusher, v_puller) < d.get(pusher, v_pusher)) {
    int n = g_.degree(v_puller);
    for (Vertex u : g_.neighbors(v_puller)) {
      if (pull_impossible(u, v_pusher)) --n;
      else tmp = u;
    }
    if (n >= 2) return false;  // room to pass: no swap needed
    if (n <= 0) break;
    v_pusher = v_puller;
    v_puller = tmp;
  }
  return d.get(puller, v_pusher) < d.get(puller, v_puller) &&
         (d.get(pusher, v_pusher) == 0 || d.get(pusher, v_puller) < d.get(pusher, v_pusher));
}

// Simulates the puller backing out: the swap is possible when it reaches a vertex with
// two free ways before returning to where the pusher started.
bool Pibt::swap_possible(Vertex v_pusher, Vertex v_puller) const
{
  const Vertex origin = v_pusher;
  Vertex tmp = -1;
  while (v_puller != origin) {
    int n = g_.degree(v_puller);
    for (Vertex u : g_.neighbors(v_puller)) {
      if (pull_impossible(u, v_pusher)) --n;
      else tmp = u;
    }
    if (n >= 2) return true;
    if (n <= 0) return false;
    v_pusher = v_puller;
    v_puller = tmp;
  }
  return false;
}

}  // namespace planner
