// LaCAM* refinement of Lacam (the "LaCAM* refinement" section of lacam.hpp): neighbour
// links, costs, the Dijkstra-style rewrite, the search after the first solution, and the
// re-basing of g when RT-LaCAM reroots.
#include <algorithm>
#include <string>

#include "planner/lacam/lacam.hpp"

namespace planner {

int32_t Lacam::edge_cost(const Vertex* a, const Vertex* b) const
{
  int32_t c = 0;
  for (int i = 0; i < n_; ++i) c += !(a[i] == goals_[i] && b[i] == goals_[i]);
  return c;
}

int32_t Lacam::heuristic(const Vertex* C)
{
  int32_t h = 0;
  for (int i = 0; i < n_; ++i) h += dist_.get(i, C[i]);
  return h;
}

// a -> b is a legal transition (b was generated from a). The link b -> a is recorded only
// if it is legal too: a rewrite re-parents along links, and a parent must be one move away.
void Lacam::link(HNode* a, HNode* b)
{
  for (const Neighbor* e = a->neighbors; e; e = e->next)
    if (e->to == b) return;
  Neighbor* e = links_.alloc(2);
  e[0] = Neighbor{b, a->neighbors, -1};
  a->neighbors = &e[0];
  if (!reversible(a, b)) return;  // e[1] stays unused (one arena slot)
  e[1] = Neighbor{a, b->neighbors, -1};
  b->neighbors = &e[1];
}

int32_t Lacam::cost(HNode* from, Neighbor* e)
{
  if (e->cost < 0) e->cost = edge_cost(from->C, e->to->C);
  return e->cost;
}

size_t Lacam::bytes_reserved() const
{
  return nodes_.bytes_reserved() + constraints_.bytes_reserved() + configs_.bytes_reserved() +
         orders_.bytes_reserved() + priorities_.bytes_reserved() + links_.bytes_reserved() +
         all_.capacity() * sizeof(HNode*) + open_.capacity() * sizeof(HNode*) + explored_.bytes_reserved();
}

// g and h of every node cost O(nodes x N) (12.9 ms at the first solution of
// warehouse-20-40-10-2-2 N = 1000): done by prepare_step() in the iterations' budgets, while
// the agents follow the first solution.
void Lacam::start_refining()
{
  refining_ = preparing_ = true;
  prepare_next_ = 0;
  pibt_.set_local_guidance(nullptr);  // refine_expand() guides its expansions one by one
  if (live_) {  // scatter_live: SUO from the start no longer shares the calls
    live_ = false;
    if (opt_.scatter_live_keep) {
      scatter_probed_ = true;  // its start is behind the agents: no restart ahead, dive from the root
    } else {  // a fresh SUO ahead on the best path, as without scatter_live
      scatter_.set_live(false);
      scatter_.clear();
      pibt_.set_scatter(nullptr);
      scatter_started_ = false;
    }
  }
  if (!timed_) prepare_step();  // no deadline: at once, in this expansion (deterministic runs)
}

// h of the next nodes and the costs of their links (cached on the links), while each fits;
// then the walk that sets every g (O(nodes + links) with the costs known). True when done.
bool Lacam::prepare_step()
{
  prepare_cost_.set_prior(2 * expand_cost_.rate());  // a node: h and its links' costs, O(N) each
  double c0 = timed_ ? thread_cpu_ms() : 0.0;
  while (prepare_next_ < all_.size()) {
    if (timed_ && !fits(prepare_cost_.predict_ms(1))) {
      prepare_cost_.forget();
      return false;
    }
    HNode* h = all_[prepare_next_++];
    h->h = heuristic(h->C);
    for (Neighbor* e = h->neighbors; e; e = e->next) cost(h, e);
    if (timed_) {
      const double c = thread_cpu_ms();
      prepare_cost_.record(1, c - c0);
      c0 = c;
    }
  }
  rebase(root_, nullptr, true);
  preparing_ = false;
  return true;
}

void Lacam::push_if_promising(HNode* h)
{
  if (h->g + h->h < goal_->g + goal_->h) open_.push_back(h);
}

// One LaCAM* iteration after the first solution (lacam3's loop body with H_goal set).
Status Lacam::refine_expand()
{
  if ((expansions_ & 63) == 0 && bytes_reserved() > opt_.refine_max_mb * (size_t{1} << 20)) {
    refining_ = false;
    refine_capped_ = true;
    return status_;
  }
  if (rewire_next_ < queue_.size()) {  // a rewiring cut at its deadline
    if (!rewire(deadline_, opt_.rewire_slice)) stalled_ = true;
    last_step_ = Step::insert;  // learnt by no cost model, like an insertion
    return status_;
  }
  if (preparing_) {
    if (!prepare_step()) stalled_ = true;  // the rest in the next calls
    last_step_ = Step::prepare;
    return status_;
  }
  if (!pending_.empty()) {  // an improved LNS window, inserted node by node, then spliced
    if (!insert_step()) stalled_ = true;
    last_step_ = Step::insert;
    return status_;
  }
  if (soc_on()) {  // a new tree path to the goal: price it by the standard SOC
    if (!best_.pricing() && (best_.empty() || goal_version_ != priced_version_)) {
      path_nodes_.clear();
      for (HNode* h = goal_; h; h = h->parent) path_nodes_.push_back(h);
      std::reverse(path_nodes_.begin(), path_nodes_.end());
      best_.start_candidate(path_nodes_);
      priced_version_ = goal_version_;
    }
    if (best_.pricing()) {
      if (!price_step()) stalled_ = true;
      last_step_ = Step::price;
      return status_;
    }
  }
  const bool all_goals = config_equal(goal_->C, goals_.data(), n_);
  // Refiner threads (lacam_threads.cpp): their windows are adopted and the path posted to
  // them before anything else (the search's own LNS goes on as without them).
  const bool threads = threads_on() && all_goals && !best_.empty();
  if (threads && thread_step()) {
    last_step_ = Step::thread;
    return status_;
  }
  // iter_refine takes LNS's turns (lacam_iter.cpp); with refiner threads it is theirs
  // (refine_thread.hpp), and the search makes no refinement steps of that kind itself.
  // Once the passes find nothing (IterRefiner::stale), LNS steps take their turns until one
  // changes the path: the copy is then made anew and the passes go on. On light instances
  // LNS's targeted windows still find what the passes do not (docs/rt_lacam_star.md, s45).
  const bool iter = opt_.iter_refine && !threads_ && soc_on() && all_goals && !best_.empty() &&
                    !(iter_ && iter_->stale() && iter_->version() == best_.version() && opt_.lns && lns_failures_ < 1000);
  const bool lns = !iter && (!opt_.iter_refine || !threads_) && opt_.lns && lns_failures_ < 1000 && all_goals && (!soc_on() || !best_.empty());
  // Engineering LaCAM* guidance (lacam_guide.cpp): SUO until done, then dives.
  const bool guide = all_goals && !goal_test_ &&
                     (dive_ ||
                      (opt_.scatter && !scatter_stopped_ && (!scatter_started_ || !scatter_.done() || scatter_.passes() > passes_dived_)) ||
                      (opt_.dive && dive_failures_ < 1000));
  // SUO's first pass and its dive take every refinement iteration (they matter most), then
  // the guide gets a third of them (half without LNS); the rest as before.
  const bool urgent = opt_.scatter && !first_dive_done_;
  // A paused dive step keeps the turn: pibt_ holds its generation (dive_pause).
  const bool guide_turn = guide && (dive_paused_ || urgent || (guide_iterations_++ % (lns || iter ? 3 : 2)) == 0 || (open_.empty() && !lns && !iter));
  // A guide step is at least one SUO slice or one dive step (dive_cost_, a PIBT call's prior).
  dive_cost_.set_prior(expand_cost_.rate());
  const double unit = std::max(expand_cost_.predict_ms(1), dive_cost_.predict_ms(1));
  const bool guide_fits = !timed_ || fits(guide_tail_.predict_ms(1) + unit);
  if (guide_turn && !guide_fits) guide_tail_.forget(), dive_cost_.forget();
  if (dive_paused_ && !guide_fits) {  // nothing else may use pibt_ before the dive step ends
    stalled_ = true;
    return status_;
  }
  if (guide_turn && guide_fits) {
    // SUO and dives stop at their deadline, but past it by up to a pass's publication: they
    // get the call's deadline less the largest such overshoot seen (decaying, step_cost.hpp),
    // in CPU time (on a loaded machine the wall-clock overshoot is mostly preemption).
    const auto deadline = deadline_;
    guide_tail_.set_prior(expand_cost_.rate());  // a pass's publication: O(N) per agent's path
    if (timed_)
      deadline_ -= std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double, std::milli>(guide_tail_.predict_ms(1)));
    const double room0 = timed_ ? room_ms() : 0.0, c0 = timed_ ? thread_cpu_ms() : 0.0;
    guide_step();
    // A step that ran to its deadline (an SUO slice, a paused dive step) swept its memory
    // through the caches: the next step is priced cold (LacamOptions::cold_end).
    if (timed_ && opt_.cold_end && room_ms() <= 0) cold_ = true;
    deadline_ = deadline;
    if (timed_) guide_tail_.record(1, std::max(0.0, thread_cpu_ms() - c0 - room0));
    guide_spent_ += timed_ ? thread_cpu_ms() - c0 : static_cast<double>(units_);
    last_step_ = Step::guide;
    return status_;
  }
  if (iter && (open_.empty() || (refine_iterations_++ & 3) != 0)) {
    if (iter_step()) {
      last_step_ = Step::thread;
      return status_;
    }
    if (open_.empty()) {  // nothing fits now: later
      stalled_ = true;
      return status_;
    }
  }
  if (lns && (open_.empty() || (refine_iterations_++ & 1) == 0)) {
    // The window is cut to what fits: a step costs about (N + 16 k) per time step (copying
    // and occupancy O(N), k A* searches); the rate is learnt (step_cost.hpp). Insertion
    // of an improved window is resumable (insert_step).
    const double per_step = static_cast<double>(n_) + 16.0 * opt_.lns_agents;
    lns_cost_.set_prior(expand_cost_.rate() / std::max(n_, 1));
    // Half the room: a step's cost varies about 2x at one size (A* successes, rewiring).
    const double fit = timed_ ? lns_cost_.units_within(0.5 * room_ms()) / per_step : 1e300;
    int window = static_cast<int>(std::min<double>(opt_.lns_window, fit));
    const bool warming = window >= kMinLnsWindow && timed_ && lns_.warm_window() < window;
    if (warming) {
      // The occupancy table's pages for this window are mapped first, in half of what is
      // left (lazy_table.hpp): a step that faulted them in cost up to 15 ms at N = 1000. The
      // step then gets the rows mapped so far, cut to the rest. Untimed runs fault them in
      // as they go (the same steps, deterministic).
      ++lns_warms_;
      lns_.warm(window, Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double, std::milli>(0.5 * room_ms())));
      const double fit_now = lns_cost_.units_within(0.5 * room_ms()) / per_step;
      window = static_cast<int>(std::min<double>({static_cast<double>(window), fit_now,
                                                  static_cast<double>(lns_.warm_window())}));
      if (opt_.cold_end) cold_ = true;  // the mapping swept the caches (cold_end)
      if (window < kMinLnsWindow) {  // the rest in the next LNS turns
        ++expansions_;
        last_step_ = Step::warm;
        return status_;
      }
    }
    if (window >= kMinLnsWindow) {
      lns_max_window_ = std::max(lns_max_window_, window);
      ++expansions_;
      if (lns_step(window)) lns_failures_ = 0;
      else ++lns_failures_;
      if (timed_ && opt_.cold_end) cold_ = true;  // its tables swept the caches (cold_end)
      // An expansion costs O(N) (one PIBT call); an LNS step O(W x N) and more: charge it in
      // expansion-equivalents, so that a budget in expansions bounds the work too.
      units_ = std::max<uint64_t>(1, lns_.work() / static_cast<uint64_t>(std::max(n_, 1)));
      // A step after mapping pages is not learnt from (its time holds the mapping's).
      last_step_ = warming ? Step::warm : Step::lns;
      last_units_ = window * per_step;
      return status_;
    }
    lns_cost_.forget();
    if (open_.empty()) {  // no window fits now: LNS again in a later call
      stalled_ = true;
      return status_;
    }
  }
  if (open_.empty() && threads) {  // the workers may still improve the path
    stalled_ = true;
    return status_;
  }
  if (open_.empty()) {  // nothing cheaper is reachable by LaCAM*
    refining_ = false;
    return status_;
  }
  // Guided by SUO's paths (PIBT keeps them once a pass is published): its own cost model.
  const bool sg = opt_.guided_cost && timed_ && pibt_.scatter() && pibt_.scatter()->ready();
  if (sg) {
    sg_cost_.set_prior(dive_cost_.samples() > 0 ? std::max(expand_cost_.rate(), dive_cost_.rate())
                                                : kGuidedPrior * expand_cost_.rate());
    if (!fits(sg_cost_.predict_ms(1))) {
      sg_cost_.forget();
      stalled_ = true;  // in a later call
      return status_;
    }
  }
  ++expansions_;
  HNode* H = open_.back();
  if (H->g >= goal_->g) {  // cannot lead to a cheaper goal
    open_.pop_back();
    return status_;
  }
  if (is_goal(H)) {  // a goal test may accept several configurations
    goal_ = H;
    open_.pop_back();
    return status_;
  }
  Constraint* L = H->pop();
  if (!L) {
    open_.pop_back();
    return status_;
  }
  grow_lowlevel(H, L);
  last_step_ = sg ? Step::sg_expansion : Step::expansion;
  if (opt_.lg_window > 0 && opt_.lg_refine) {  // guided when it fits (lg_cost_), unguided else
    lg_cost_.set_prior(2 * expand_cost_.rate());
    // No forget() when it does not fit (unlike the other steps): its cost is O(N x window)
    // every time, not a spike, and retrying it as the rate decayed overran every ~40th call.
    // Twice the rate must fit: one generation's A*s vary about 2x with the collisions met
    // (measured: p99 1.9 ms at a 1 ms cutoff with the rate alone, RefineBudget test below).
    const bool lg = !timed_ || fits(2.0 * lg_cost_.predict_ms(1));
    if (lg) last_step_ = Step::lg_expansion, ++guided_;
    pibt_.set_local_guidance(lg ? &lg_ : nullptr);
  }
  const bool made = generate_best(H, L);
  pibt_.set_local_guidance(nullptr);
  if (!made) return status_;
  const uint64_t hash = config_hash(scratch_.data(), n_);
  if (HNode* known = explored_.find(scratch_.data(), hash)) {
    link(H, known);
    rewrite(H, known, deadline_, opt_.rewire_slice);  // cut at the deadline: resumed by the next step
    push_if_promising(rng_.uniform() < opt_.restart_rate ? root_ : known);
  } else {
    HNode* h = new_node(scratch_.data(), H, hash);
    h->g = H->g + edge_cost(H->C, h->C);
    h->h = heuristic(h->C);
    link(H, h);
    explored_.insert(h);
    push_if_promising(h);
  }
  return status_;
}

// Only the window's configurations are copied (the whole path was O(T x N) per step, 6-7 ms
// at warehouse-20-40-10-2-2 N = 1000); the improved window is inserted from its first node,
// and its last configuration is the path's own node there, which the rewiring then lowers.
bool Lacam::lns_step(int window)
{
  const bool soc = soc_on();
  if (soc) {
    path_nodes_ = best_.nodes();
  } else {
    path_nodes_.clear();
    for (HNode* h = goal_; h; h = h->parent) path_nodes_.push_back(h);
    std::reverse(path_nodes_.begin(), path_nodes_.end());
  }
  const int T = static_cast<int>(path_nodes_.size()) - 1;
  if (T < 1) return false;
  int W = std::min(window, T);
  int t0 = T > W ? static_cast<int>(rng_.below(static_cast<uint32_t>(T - W + 1))) : 0;
  int seed = -1;
  if (soc) {
    // A delayed agent by roulette over the path (its last arrival less its distance), and a
    // window that ends a little after that arrival: only there can its standard SOC drop.
    int64_t total = 0;
    for (int i = 0; i < n_; ++i) total += std::max<int64_t>(0, best_.last_off(i) + 1 - dist_.get(i, root_->C[i]));
    if (total > 0) {
      int64_t r = static_cast<int64_t>(rng_.uniform() * static_cast<double>(total));
      for (int i = 0; i < n_ && seed < 0; ++i) {
        r -= std::max<int64_t>(0, best_.last_off(i) + 1 - dist_.get(i, root_->C[i]));
        if (r < 0) seed = i;
      }
      if (seed >= 0) {
        // Not from the root: the agents may move on before the window is inserted, and a
        // window that starts behind the root can no longer be followed.
        const int t1 = std::min(T, best_.last_off(seed) + 1 + static_cast<int>(rng_.below(static_cast<uint32_t>(W / 4 + 1))));
        t0 = std::max(std::min(kLnsLead, t1 - 1), t1 - W);
        W = t1 - t0;
        if (W < 1) return false;
      }
    }
  }
  window_.resize(static_cast<size_t>(W) + 1);
  for (int t = 0; t <= W; ++t) window_[t].assign(path_nodes_[t0 + t]->C, path_nodes_[t0 + t]->C + n_);
  lns_.set_window(W);
  if (soc) {
    stays_.resize(n_);
    for (int i = 0; i < n_; ++i) stays_[i] = best_.last_off(i) < t0 + W;
  }
  if (!lns_.step(window_, goals_, opt_.lns_agents, rng_, deadline_, soc ? stays_.data() : nullptr, seed)) return false;
  pending_.swap(window_);  // inserted by insert_step(), now or in the next calls
  pending_next_ = 1;
  pending_prev_ = path_nodes_[t0];
  splice_from_ = path_nodes_[t0];
  spliced_.clear();
  splice_set_ = lns_.last_set();
  if (!timed_) insert_step();  // no deadline: at once, in this step (deterministic runs)
  return true;
}

// A new node costs O(N) (hash, priorities, their order) and its rewiring more: a whole
// window (40 nodes, 0.8-1.5 ms at N = 400) is too much for one step, so it goes in pieces.
// Each piece leaves a valid chain of linked nodes; g(goal) drops when the last one links.
bool Lacam::insert_step()
{
  insert_cost_.set_prior(expand_cost_.rate());
  double c0 = timed_ ? thread_cpu_ms() : 0.0;
  while (pending_next_ < pending_.size()) {
    if (timed_ && !fits(insert_cost_.predict_ms(1))) {
      insert_cost_.forget();
      return false;
    }
    pending_prev_ = step_to(pending_prev_, pending_[pending_next_++].data());
    spliced_.push_back(pending_prev_);
    if (timed_) {
      const double c = thread_cpu_ms();
      insert_cost_.record(1, c - c0);
      c0 = c;
    }
  }
  // soc: the window is followed if it lowers the standard SOC, whatever the tree's loss says.
  // Pricing it scans the path for each agent that moved (a refiner's window may move
  // hundreds): a step of its own, when it fits.
  if (soc_on()) {
    const double units = static_cast<double>(splice_set_.size() + 1) * static_cast<double>(best_.nodes().size());
    splice_cost_.set_prior(kSplicePrior);
    if (timed_ && !fits(splice_cost_.predict_ms(units))) {
      splice_cost_.forget();
      return false;
    }
    const bool ok = best_.splice(splice_from_, spliced_, splice_set_);
    if (timed_) splice_cost_.record(units, thread_cpu_ms() - c0);
    if (threads_) thread_spliced(ok);  // a worker's window (lacam_threads.cpp), if it was one
    if (iter_adopting_) iter_spliced(ok);  // iter_'s window (lacam_iter.cpp)
  }
  pending_.clear();
  pending_next_ = 0;
  pending_prev_ = nullptr;
  return true;
}

// Label-correcting Dijkstra from a new link's two ends: a node whose g drops takes the
// relaxing node as parent, and the drop propagates along the links. Costs are positive off
// the goal configuration, so parents stay a tree and the root (g = 0) is never re-parented.
bool Lacam::rewrite(HNode* a, HNode* b, Clock::time_point deadline, int max_nodes)
{
  queue_.push_back(a);
  queue_.push_back(b);
  return rewire(deadline, max_nodes);
}

// One node at least per call (progress), then until the deadline or max_nodes (0: no cap).
bool Lacam::rewire(Clock::time_point deadline, int max_nodes)
{
  for (int k = 0; rewire_next_ < queue_.size(); ++k) {
    if (k > 0 && ((max_nodes > 0 && k >= max_nodes) || (deadline != Clock::time_point::max() && Clock::now() >= deadline))) {
      ++rewire_cuts_;
      return false;
    }
    HNode* from = queue_[rewire_next_++];
    for (Neighbor* e = from->neighbors; e; e = e->next) {
      HNode* to = e->to;
      const int64_t g = from->g + cost(from, e);
      if (g >= to->g) continue;
      to->g = g;
      to->parent = from;
      if (to == goal_) ++goal_version_;
      queue_.push_back(to);
      if (to->g + to->h < goal_->g + goal_->h) open_.push_back(to);
    }
  }
  queue_.clear();
  rewire_next_ = 0;
  return true;
}

// Recomputes g over the tree below new_root (the whole tree), walking from a node x to its
// tree children (links y with y->parent == x). Along an edge that kept its direction the
// cost is g_old(y) - g_old(x); the reversed edge new_root -> old_root, or every edge when
// `explicit_costs`, is costed explicitly.
void Lacam::rebase(HNode* new_root, HNode* old_root, bool explicit_costs)
{
  walk_.clear();
  walk_.emplace_back(new_root, new_root->g);
  new_root->g = 0;
  while (!walk_.empty()) {
    const auto [x, x_old] = walk_.back();
    walk_.pop_back();
    for (Neighbor* e = x->neighbors; e; e = e->next) {
      HNode* y = e->to;
      if (y->parent != x) continue;
      const int64_t y_old = y->g;
      const bool reversed = x == new_root && y == old_root;
      y->g = x->g + (explicit_costs || reversed ? cost(x, e) : y_old - x_old);
      walk_.emplace_back(y, y_old);
    }
  }
}

// Monte-Carlo generation (lacam3's set_new_config): the rollout of least edge cost + h wins.
bool Lacam::mc_keep(const Vertex* from, const Vertex* C)
{
  const int64_t f = static_cast<int64_t>(edge_cost(from, C)) + heuristic(C);
  if (f >= mc_f_) return false;
  mc_f_ = f;
  mc_best_.assign(C, C + n_);
  return true;
}

bool Lacam::generate_best(const HNode* H, const Constraint* L)
{
  if (opt_.mc_rollouts <= 1 || !opt_.mc_refine) return pibt_.generate(H->C, H->order, L, scratch_.data(), rng_);
  mc_f_ = INT64_MAX;
  mc_try_.resize(n_);
  for (int k = 0; k < opt_.mc_rollouts; ++k)
    if (pibt_.generate(H->C, H->order, L, mc_try_.data(), rng_)) mc_keep(H->C, mc_try_.data());
  if (mc_f_ == INT64_MAX) return false;
  std::copy(mc_best_.begin(), mc_best_.end(), scratch_.begin());
  return true;
}

bool Lacam::price_step()
{
  price_cost_.set_prior(expand_cost_.rate());  // a node: O(N), like an expansion's PIBT call at most
  double c0 = timed_ ? thread_cpu_ms() : 0.0;
  // Against an expansions budget kPricedPerUnit nodes count as one expansion: a node is N
  // comparisons, an expansion a PIBT call over N agents (measured: ~20x dearer).
  constexpr uint64_t kPricedPerUnit = 16;
  ++expansions_;
  uint64_t k = 0;
  const uint64_t most = std::max<uint64_t>(left_, 1) > UINT64_MAX / kPricedPerUnit ? UINT64_MAX
                                                                                   : std::max<uint64_t>(left_, 1) * kPricedPerUnit;
  while (best_.pricing()) {
    if ((timed_ && !fits(price_cost_.predict_ms(1))) || k >= most) {
      if (timed_ && k < most) price_cost_.forget();
      units_ = std::max<uint64_t>(k / kPricedPerUnit, 1);
      return false;
    }
    best_.price_node();
    ++k;
    if (timed_) {
      const double c = thread_cpu_ms();
      price_cost_.record(1, c - c0);
      c0 = c;
    }
  }
  units_ = std::max<uint64_t>(k / kPricedPerUnit, 1);
  return true;
}

std::vector<Config> Lacam::best_path() const
{
  if (!soc_on() || best_.empty()) return path(goal_);
  std::vector<Config> out;
  for (const HNode* h : best_.nodes()) out.emplace_back(h->C, h->C + n_);
  return out;
}

int Lacam::best_steps() const
{
  if (soc_on() && !best_.empty()) return static_cast<int>(best_.nodes().size()) - 1;
  if (!goal_) return -1;
  int steps = 0;
  for (const HNode* h = goal_; h->parent; h = h->parent) ++steps;
  return steps;
}

Config Lacam::best_at(int k) const
{
  const HNode* h = nullptr;
  if (soc_on() && !best_.empty()) {
    h = best_.nodes().at(static_cast<size_t>(k));
  } else {
    h = goal_;
    for (int back = best_steps() - k; back > 0; --back) h = h->parent;
  }
  return Config(h->C, h->C + n_);
}

const HNode* Lacam::best_next() const
{
  if (!soc_on() || best_.empty()) return nullptr;
  const auto& p = best_.nodes();
  return p.size() >= 2 ? p[1] : p[0];
}

bool Lacam::check_costs(std::string* why) const
{
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!refining_ || preparing_) return fail("costs are kept only while refining");
  if (root_->g != 0) return fail("root g is " + std::to_string(root_->g));
  for (const HNode* s : all_) {
    int64_t sum = 0;
    for (const HNode* h = s; h->parent; h = h->parent) sum += edge_cost(h->parent->C, h->C);
    if (sum != s->g)
      return fail("node " + std::to_string(s->id) + ": g " + std::to_string(s->g) + ", tree path cost " +
                  std::to_string(sum));
  }
  return true;
}

}  // namespace planner
