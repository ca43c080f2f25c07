#include "planner/lacam/lacam.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "planner/lacam/immobile.hpp"
#include "planner/lacam/priority.hpp"

namespace planner {

const char* to_string(Status s)
{
  switch (s) {
    case Status::Searching: return "searching";
    case Status::Solved: return "solved";
    case Status::NoSolution: return "no_solution";
  }
  return "?";
}

Lacam::Lacam(const Graph& g, DistTable& dist, LacamOptions opt, ActionPreference* pref)
    : g_(g), dist_(dist), opt_(opt), pibt_(g, dist, opt.swap), rng_(opt.seed), lns_(g, dist, opt.lns_window, opt.lns_neighbourhood, opt.objective), scatter_(g, dist), lg_(g, dist), moves_(g.max_degree() + 1)
{
  pibt_.set_preference(pref);
  pibt_.set_free_first(opt.free_first);
  if (opt.highways > 0) {
    auto costs = highway_costs(g, HighwayOptions{opt.highways, opt.highway_min_run});
    if (!costs.empty()) {
      for (uint8_t c : costs) highway_arcs_ += c > 0;
      // As many tables as the plain distances keep (lifelong runs visit thousands of goals).
      auto cache = std::make_shared<DistCache>(g, dist.cache()->max_tables());
      cache->set_arc_costs(std::move(costs));
      guide_ = std::make_unique<DistTable>(g, std::move(cache));
      pibt_.set_guide(guide_.get());
    }
  }
  lg_.set_window(opt.lg_window > 0 ? opt.lg_window : opt.lg_window_unpaused);
  lg_.set_collision_weight(opt.lg_collision_weight);
  lg_.set_rest_on_goal(opt.lg_rest);
  lg_.set_refresh(opt.lg_refresh);
  lg_.set_budget(opt.lg_budget);
  lg_.set_repair(opt.lg_repair);
  if (opt.lg_window > 0 || opt.lg_window_unpaused > 0) lg_.prepare();  // its tables, outside any iteration
  lns_.set_stop_cost(opt.lns_stop_cost);
  lns_.set_count_moves(opt.lns_count_moves);
  lns_wanted_ = opt.lns;
  iter_wanted_ = opt.iter_refine;
  if (opt.zones) {  // LNS, iterative refinement and the refiner threads plan without PIBT's zone rule
    pibt_.set_zones(opt.zones.get());
    lns_wanted_ = opt_.lns = false;
    iter_wanted_ = opt_.iter_refine = false;
    opt_.refine_threads = 0;
  }
  start_threads();
}

void Lacam::set_immobile(const std::vector<uint8_t>& immobile)
{
  immobile_ = immobile;
  pibt_.set_immobile(immobile);
  opt_.lns = lns_wanted_ && !any_immobile(immobile);  // LNS's A* would move them
  opt_.iter_refine = iter_wanted_ && !any_immobile(immobile);  // and so would iterative refinement's SIPP
  if (iter_wanted_ && !opt_.iter_refine && (iter_win_ready_ || iter_adopting_)) {  // its window may move them
    if (iter_adopting_) pending_.clear(), pending_next_ = 0, pending_prev_ = nullptr;
    iter_win_ready_ = iter_adopting_ = false;
    if (iter_) iter_->clear();
  }
}

void Lacam::reset(const Config& start, const Config& goals, GoalTest test, const float* priorities,
                  const int32_t* order)
{
  n_ = static_cast<int>(start.size());
  goals_ = goals;
  goal_test_ = std::move(test);
  dist_.set_goals(goals);
  if (guide_) guide_->set_goals(goals);
  pibt_.set_goals(goals);
  nodes_.reset();
  constraints_.reset();
  configs_.reset();
  orders_.reset();
  priorities_.reset();
  links_.reset();
  refining_ = refine_capped_ = preparing_ = false;
  prepare_next_ = 0;
  pending_.clear();
  pending_next_ = 0;
  pending_prev_ = nullptr;
  if (iter_) iter_->clear();  // its copy was of the old tree's path
  iter_win_ready_ = iter_adopting_ = false;
  root_step_ = 0;
  threads_park();
  // A paused expansion belonged to the old tree. If none of that tree's expansions had ended,
  // the new tree's first one ends in its call: resets (goal changes) cannot keep every
  // expansion from ending.
  may_pause_ = !(gen_ != Gen::none && !ended_);
  ended_ = false;
  gen_ = Gen::none;
  refine_iterations_ = guide_iterations_ = 0;
  lns_failures_ = 0;
  debt_ = 0;
  explored_.clear();
  explored_.set_num_agents(n_);
  open_.clear();
  all_.clear();
  queue_.clear();  // a cut rewiring belonged to the old tree
  rewire_next_ = 0;
  goal_ = nullptr;
  best_.reset(goals_);
  goal_version_ = priced_version_ = 0;
  splice_from_ = nullptr;
  spliced_.clear();
  scratch_.assign(n_, -1);
  pibt_.set_scatter(nullptr);
  pibt_.set_local_guidance(opt_.lg_window > 0 && opt_.lg_first ? &lg_ : nullptr);
  lg_gated_ = false;
  lg_.forget_first();
  scatter_.clear();
  scatter_started_ = first_dive_done_ = false;
  scatter_root_ = nullptr;
  scatter_probed_ = guided_dive_ = scatter_stopped_ = false;
  passes_dived_ = 0;
  dive_ = nullptr;
  dive_paused_ = false;
  dive_failures_ = 0;
  if (opt_.scatter_first && !test) {
    scatter_.reset(start, opt_.scatter_margin, opt_.seed + 3, opt_.scatter_max_passes);
    scatter_started_ = true;
  }
  live_ = false;
  scatter_.set_live(false);
  if (opt_.scatter_live && opt_.refine && opt_.scatter && !opt_.scatter_first && !test) {
    // SUO from the start, its paths guiding PIBT one by one as they end (search(): live_slice).
    scatter_.set_live(true);
    scatter_.reset(start, opt_.scatter_margin, opt_.seed + 3, opt_.scatter_max_passes);
    scatter_started_ = live_ = true;
    scatter_reroots0_ = reroots_;
    scatter_lead_ = 0;
    guide_spent_ = 0;
    pibt_.set_scatter(&scatter_);
  }
  // PIBT's first call reads every agent's distance one BFS level past its start: a lazy BFS
  // of that level for N tables (11 ms in the first iteration of warehouse-20-40-10-2-2,
  // N = 1000). Here it is part of the reset (setup), not of an iteration's budget.
  // The same for PIBT's ranking distances (highways).
  for (int i = 0; i < n_; ++i)
    for (Vertex u : g_.neighbors(start[i])) {
      dist_.get(i, u);
      if (guide_) guide_->get(i, u);
    }
  // On a directed graph a goal may be unreachable from its start although both lie in one
  // connected piece: refuse it here, since the search would only stop after exhausting
  // every reachable configuration.
  if (g_.directed() && !test)
    for (int i = 0; i < n_; ++i)
      if (dist_.get(i, start[i]) == DistTable::kInf)
        throw std::invalid_argument("lacam: agent " + std::to_string(i) + ": goal " + std::to_string(goals[i]) +
                                    " is unreachable from start " + std::to_string(start[i]) + " along the one-way arcs");
  root_ = new_node(start.data(), nullptr, config_hash(start.data(), n_), priorities, priorities ? order : nullptr);
  scatter_root_ = root_;
  explored_.insert(root_);
  open_.push_back(root_);
  status_ = Status::Searching;
}

HNode* Lacam::new_node(const Vertex* C, HNode* parent, uint64_t hash, const float* root_priorities,
                       const int32_t* root_order)
{
  float* prio = nullptr;
  int32_t* order = nullptr;
  HNode* h = alloc_node(C, &prio, &order);
  if (parent) {
    next_priorities(h->C, n_, dist_, parent->priorities, prio);
    std::copy(parent->order, parent->order + n_, order);
    sort_by_priority(prio, n_, order);
  } else {
    if (root_priorities) std::copy(root_priorities, root_priorities + n_, prio);
    else init_priorities(h->C, n_, dist_, prio);
    if (root_order) {  // the same total order as initial_order's sort, from a near-sorted start
      std::copy(root_order, root_order + n_, order);
      sort_by_priority(prio, n_, order);
    } else {
      initial_order(prio, n_, order);
    }
  }
  add_node(h, parent, hash);
  return h;
}

HNode* Lacam::alloc_node(const Vertex* C, float** prio, int32_t** order)
{
  HNode* h = nodes_.alloc(1);
  *h = HNode{};
  Vertex* c = configs_.alloc(n_);
  std::copy(C, C + n_, c);
  h->C = c;
  h->priorities = *prio = priorities_.alloc(n_);
  h->order = *order = orders_.alloc(n_);
  return h;
}

void Lacam::add_node(HNode* h, HNode* parent, uint64_t hash)
{
  h->parent = parent;
  h->hash = hash;
  h->id = static_cast<uint32_t>(all_.size());
  Constraint* root = constraints_.alloc(1);
  *root = Constraint{};
  h->push(root);
  all_.push_back(h);
}

bool Lacam::is_goal(const HNode* h) const
{
  return goal_test_ ? goal_test_(h->C) : config_equal(h->C, goals_.data(), n_);
}

Status Lacam::expand()
{
  if (refining_) return refine_expand();
  if (status_ != Status::Searching) return status_;
  if (gen_ != Gen::none) return finish_expansion();  // a paused expansion goes on first
  if (open_.empty()) return status_ = Status::NoSolution;
  if (opt_.scatter_first && scatter_started_ && scatter_step()) return status_;  // SUO first (lacam3's order)
  HNode* H = open_.back();
  if (is_goal(H)) {
    goal_ = H;
    status_ = Status::Solved;
    solved_expansions_ = expansions_;
    solved_explored_ = explored_.size();
    if (opt_.refine) start_refining();
    return status_;
  }
  ++expansions_;
  Constraint* L = H->pop();
  if (!L) {  // every successor of H has been tried
    open_.pop_back();
    return status_;
  }
  grow_lowlevel(H, L);
  last_step_ = Step::expansion;

  gen_rng_ = rng_;
  pibt_.start(H->C, H->order, L);
  mc_done_ = 0, mc_f_ = INT64_MAX;
  gen_ = Gen::generating;
  gen_h_ = H;
  gen_l_ = L;
  gen_cpu_ms_ = 0;
  return finish_expansion();
}

// The rest of an expansion, in steps that can each stop at the running call's deadline
// (resumable): PIBT's agents, then the successor's lookup, priorities and order, all O(N).
Status Lacam::finish_expansion()
{
  const bool pausable = opt_.resumable && may_pause_ && pause_at_ != Clock::time_point::max();
  const Clock::time_point at = pausable ? pause_at_ : Clock::time_point::max();
  last_step_ = Step::partial;
  // The insertion is one step while it is one chunk or two (small N).
  const bool tail_pausable = pausable && n_ > kTailChunk;
  int units = 0;  // of this call; the clock is read every kTailEvery
  auto stop = [&] { return tail_pausable && ++units % kTailEvery == 0 && Clock::now() >= at; };
  if (gen_ == Gen::generating) {
    Pibt::Gen r;
    for (;;) {
      if (!pibt_.pending()) {  // cancelled by set_immobile(): again, from the same draws
        rng_ = gen_rng_;
        mc_done_ = 0, mc_f_ = INT64_MAX;
        pibt_.start(gen_h_->C, gen_h_->order, gen_l_);
      }
      const uint64_t p0 = pibt_.plans();
      r = pibt_.resume(rng_, at);
      agents_planned_ += pibt_.plans() - p0;
      if (r == Pibt::Gen::paused) return status_;
      if (mc_search_rollouts() <= 1) break;
      if (r == Pibt::Gen::done) mc_keep(gen_h_->C, pibt_.result());
      if (++mc_done_ < mc_search_rollouts()) {  // the next rollout, in this call while it lasts
        pibt_.start(gen_h_->C, gen_h_->order, gen_l_);
        continue;
      }
      r = mc_f_ < INT64_MAX ? Pibt::Gen::done : Pibt::Gen::failed;
      break;
    }
    if (r == Pibt::Gen::failed) {  // the fixed agents collide, or PIBT failed: no successor
      gen_ = Gen::none;
      ended_ = may_pause_ = true;
      last_step_ = Step::expansion;
      return status_;
    }
    if (tail_pausable && Clock::now() >= at) {
      gen_ = Gen::lookup;
      return status_;
    }
    units = 1;
    gen_ = Gen::lookup;
  }
  HNode* H = gen_h_;
  if (gen_ == Gen::lookup) {
    const Vertex* C = mc_search_rollouts() > 1 ? mc_best_.data() : pibt_.result();  // kept until the next start()
    gen_hash_ = config_hash(C, n_);
    if (HNode* known = explored_.find(C, gen_hash_)) {
      if (opt_.refine) link(H, known);
      open_.push_back(known);  // revisit: its next constraint yields another successor
      gen_ = Gen::none;
      ended_ = may_pause_ = true;
      last_step_ = Step::expansion;
      return status_;
    }
    gen_node_ = alloc_node(C, &gen_prio_, &gen_order_);
    gen_ = Gen::priorities, gen_k_ = 0;
  }
  if (gen_ == Gen::priorities) {
    for (; gen_k_ < n_; gen_k_ += kTailChunk) {
      if (stop()) return status_;
      next_priorities(gen_node_->C, gen_k_, std::min(n_, gen_k_ + kTailChunk), dist_, H->priorities, gen_prio_);
    }
    std::copy(H->order, H->order + n_, gen_order_);
    gen_ = Gen::order, gen_k_ = 0;
  }
  for (; gen_k_ < n_; gen_k_ += kTailChunk) {  // Gen::order: new_node's sort, in pieces
    if (stop()) return status_;
    insert_by_priority(gen_prio_, gen_order_, gen_k_, std::min(n_, gen_k_ + kTailChunk));
  }
  HNode* h = gen_node_;
  add_node(h, H, gen_hash_);
  if (opt_.refine) link(H, h);
  explored_.insert(h);
  open_.push_back(h);
  gen_ = Gen::none;
  ended_ = may_pause_ = true;
  last_step_ = Step::expansion;
  return status_;
}

// Grow the low-level tree lazily: children fix the next agent in H's order.
void Lacam::grow_lowlevel(HNode* H, const Constraint* L)
{
  if (L->depth >= n_) return;
  const int32_t i = H->order[L->depth];
  const Vertex v = H->C[i];
  const auto nb = g_.neighbors(v);
  Vertex* moves = moves_.data();
  int k = 0;
  const bool stays = !immobile_.empty() && immobile_[i];  // an immobile agent's one move
  if (!stays)
    for (Vertex u : nb) moves[k++] = u;
  moves[k++] = v;
  rng_.shuffle(moves, k);
  Constraint* kids = constraints_.alloc(k);
  for (int m = 0; m < k; ++m) {
    kids[m] = Constraint{L, nullptr, i, moves[m], L->depth + 1};
    H->push(&kids[m]);
  }
}

Status Lacam::search(const Budget& b, bool until_solved)
{
  const auto t0 = Clock::now();
  const auto deadline = b.deadline_from(t0);
  timed_ = deadline != Clock::time_point::max();
  // The reroot after this call walks the tree while refining: its predicted cost stays free.
  deadline_ = deadline;
  if (timed_ && refining_ && !preparing_)
    deadline_ -= std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double, std::milli>(rebase_cost_.predict_ms(1)));
  // With a reserve, the costliest expansion of this call so far counts too (on this thread's
  // CPU time, which preemption does not inflate; an LNS step: its cost over its units).
  const bool reserving = b.reserve_ms > 0 && timed_;
  double cpu_last = timed_ ? thread_cpu_ms() : 0.0;
  max_unit_ms_ = 0;
  uint64_t done = 0;
  stalled_ = cold_ = false;
  // PIBT's ranking distances (highways) keep to the same deadline as the plain ones: past
  // it they answer lower bounds too (dist_cache.hpp), so no table grows past a step's budget.
  if (guide_) guide_->cache()->set_deadline(dist_.cache()->deadline());
  if (threads_ && refining_ && !until_solved) threads_exchange();  // the iteration boundary
  // An LNS step larger than an expansions budget is paid off by the next calls (refinement
  // only: debt_ is 0 until the first solution, so LaCAM's search is never skipped).
  if (refining_ && !until_solved && debt_ > 0) {
    const uint64_t paid = std::min(debt_, b.expansions);
    debt_ -= paid;
    done = paid;
    if (done >= b.expansions) return status_;
  }
  if (live_ && !refining_ && status_ == Status::Searching) live_slice(b, t0, deadline, done);
  // lg_window_unpaused: guided while no expansion can pause (every iteration one expansion);
  // set per call, it takes effect at PIBT's next start().
  if (opt_.lg_window == 0 && opt_.lg_window_unpaused > 0 && !refining_ && status_ == Status::Searching)
    pibt_.set_local_guidance(timed_ && opt_.resumable && b.ms < opt_.pause_min_ms ? &lg_ : nullptr);
  bool first = true;
  // A LaCAM expansion may stop here (resumable), unless the cutoff is below pause_min_ms.
  const bool pausing = opt_.resumable && b.ms >= opt_.pause_min_ms;
  pause_at_ = pausing ? deadline : Clock::time_point::max();
  while (status_ == Status::Searching || (refining_ && !until_solved)) {
    // Refinement is never forced: not even one step starts unless it fits. Before the first
    // solution one expansion always runs (progress), the next ones as the paper's loop or,
    // with a reserve, while the costliest one so far fits.
    if (timed_) {
      if (refining_) {
        // After a step that swept the caches (cold_end) the next one is priced at cold_factor
        // x the rate; not fitting then is no spike to forget.
        cold_steps_ += cold_;
        if (!fits(expand_cost_.predict_ms(cold_ ? opt_.cold_factor : 1))) {
          if (!cold_) expand_cost_.forget();
          break;
        }
        cold_ = false;
      } else if (!first) {
        // A resumable expansion stops at the deadline itself: no reserve for it.
        if (reserving && !(pausing && may_pause_)) {
          const double r = std::max(b.reserve_ms, max_unit_ms_);
          if (Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(r)) >=
              deadline)
            break;
        } else if (Clock::now() >= deadline) {
          break;
        }
      }
    }
    first = false;
    // lg_gate: the first search stays guided only if the start is congested enough and, in a
    // timed call, a guided expansion (the first, every agent planned: the dearest) fits the
    // cutoff; decided once, when the first N paths are planned and that expansion is learnt.
    // It takes effect at PIBT's next start().
    if (opt_.lg_gate > 0 && !lg_gated_ && !refining_ && lg_.first_conflicted() >= 0 &&
        (!timed_ || lg_cost_.samples() > 0)) {
      lg_gated_ = true;
      if (lg_.first_conflicted() < opt_.lg_gate || (timed_ && lg_cost_.predict_ms(1) > b.ms))
        pibt_.set_local_guidance(nullptr);
    }
    units_ = 1;
    left_ = b.expansions - done;
    last_step_ = Step::none;
    expand();
    if (last_step_ == Step::partial) units_ = 0;  // an expansion counts once, when it ends
    done += units_;
    if (timed_) {
      const double c = thread_cpu_ms();
      const double dc = c - cpu_last;
      cpu_last = c;
      if (last_step_ == Step::partial) gen_cpu_ms_ += dc;  // the expansion's cost is learnt whole
      // A guided expansion of the first search is learnt apart (lg_cost_): refinement's
      // unguided ones are cheaper, and expand_cost_ gates every refinement step.
      if (last_step_ == Step::expansion)
        (!refining_ && pibt_.local_guidance() ? lg_cost_ : expand_cost_).record(1, dc + gen_cpu_ms_), gen_cpu_ms_ = 0;
      else if (last_step_ == Step::lg_expansion) lg_cost_.record(1, dc);
      else if (last_step_ == Step::sg_expansion) sg_cost_.record(1, dc), expand_cost_.record(1, dc);
      else if (last_step_ == Step::lns) lns_cost_.record(last_units_, dc);
      max_unit_ms_ = std::max(max_unit_ms_, dc / static_cast<double>(std::max<uint64_t>(units_, 1)));
    }
    if (done >= b.expansions) {
      if (b.expansions != Budget{}.expansions) debt_ = done - b.expansions;
      break;
    }
    if (stalled_) break;
  }
  pause_at_ = Clock::time_point::max();  // expand() called alone never pauses
  return status_;
}

// scatter_live: SUO's share of a call before the first solution, first (its paths guide the
// expansions that follow): timed, until share x the call's time; by expansions, share x the
// budget in SUO's work units (N per expansion, as scatter_step charges), counted as done.
void Lacam::live_slice(const Budget& b, Clock::time_point t0, Clock::time_point deadline, uint64_t& done)
{
  if (scatter_.done()) return;
  const double share = std::clamp(opt_.scatter_live_share, 0.0, 1.0);
  const uint64_t n = static_cast<uint64_t>(std::max(n_, 1));
  if (timed_) {
    const auto until = t0 + std::chrono::duration_cast<Clock::duration>((deadline - t0) * share);
    while (!scatter_.done() && Clock::now() < until) {
      if (scatter_.pass_complete()) scatter_.publish(until);
      else scatter_.step(until, UINT64_MAX, false);
    }
    return;
  }
  if (b.expansions == Budget{}.expansions) {  // no budget: the whole SUO first (scatter_first)
    scatter_.step(Clock::time_point::max());
    return;
  }
  const uint64_t units = static_cast<uint64_t>(share * static_cast<double>(b.expansions));
  if (units == 0) return;
  scatter_.step(Clock::time_point::max(), units * n);
  done += std::min<uint64_t>(units, std::max<uint64_t>(1, scatter_.work() / n));
}

double Lacam::room_ms() const
{
  if (deadline_ == Clock::time_point::max()) return 1e300;
  return std::chrono::duration<double, std::milli>(deadline_ - Clock::now()).count();
}

std::vector<Config> Lacam::path(const HNode* to) const
{
  std::vector<Config> out;
  for (const HNode* h = to; h; h = h->parent) out.emplace_back(h->C, h->C + n_);
  std::reverse(out.begin(), out.end());
  return out;
}

const HNode* Lacam::next_toward(const HNode* target) const
{
  if (!target || target == root_) return root_;
  const HNode* h = target;
  while (h->parent != root_) h = h->parent;
  return h;
}

bool Lacam::reversible(const HNode* a, const HNode* b) const
{
  if (!g_.directed()) return true;
  for (int i = 0; i < n_; ++i)
    if (a->C[i] != b->C[i] && !g_.adjacent(b->C[i], a->C[i])) return false;
  return true;
}

void Lacam::reroot(const HNode* child)
{
  if (child == root_) return;
  ++reroots_;
  ++root_step_;
  HNode* c = all_[child->id];  // non-const handle of the same node
  HNode* old = root_;
  if (!reversible(old, c)) {
    // The old root cannot be reached back from c: its link under c is kept for the tree's
    // shape only. The goal's tree path leads from c away from it, and with refinement over
    // no rewrite or rebase walks it again.
    if (!goal_) throw std::logic_error("lacam: reroot over a one-way move before a goal node is known");
    refining_ = preparing_ = false;
  }
  old->parent = c;
  c->parent = nullptr;
  root_ = c;
  // A candidate the agents left (the followed path is not its tree path, e.g. after an LNS
  // splice) is carried on from the new root, else a cheaper goal found meanwhile (a winning
  // dive) would never be followed. Priced again from scratch instead (the first version of
  // reprice), a candidate that takes more than one call was cut by every move: 113 restarts
  // and no refinement else in a run of warehouse-10-20-10-2-1 N = 200 scen 2, 5 expansions
  // per iteration (pricing goes first).
  if (best_.advance(old, c, opt_.reprice && refining_)) ++reprices_;
  if (refining_ && !preparing_) {  // timed: search() keeps the next one's cost free
    const double c0 = thread_cpu_ms();
    rebase(c, old, false);
    rebase_cost_.record(1, thread_cpu_ms() - c0);
  }
}

void Lacam::waited()
{
  if (soc_on() && best_.nodes().size() >= 2 && best_.nodes()[1] == root_) best_.advance(root_, root_, false);
}

bool Lacam::check_tree(std::string* why) const
{
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!root_) return fail("no root");
  if (root_->parent) return fail("root has a parent");
  // 0 = unknown, 1 = on the current walk, 2 = reaches the root
  std::vector<uint8_t> mark(all_.size(), 0);
  mark[root_->id] = 2;
  std::vector<const HNode*> walk;
  for (const HNode* s : all_) {
    walk.clear();
    const HNode* h = s;
    while (mark[h->id] == 0) {
      mark[h->id] = 1;
      walk.push_back(h);
      if (!h->parent) return fail("node " + std::to_string(h->id) + " has no parent but is not the root");
      h = h->parent;
    }
    if (mark[h->id] == 1) return fail("cycle through node " + std::to_string(h->id));
    for (const HNode* w : walk) mark[w->id] = 2;
  }
  if (explored_.size() != all_.size()) return fail("explored table and node list differ in size");
  return true;
}

}  // namespace planner
