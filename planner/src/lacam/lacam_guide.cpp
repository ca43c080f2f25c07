// Engineering LaCAM* guidance of the refinement (LacamOptions::scatter, dive, scatter_first;
// lacam.hpp): SUO computed in the refinement's budget, and dives -- PIBT rollouts from the
// current root to the goals -- whose configurations are inserted and rewired like an LNS path.
#include <algorithm>

#include "planner/lacam/lacam.hpp"

namespace planner {

// Known or new node for configuration C reached from `from`, linked to it; a known one is
// rewired (its g, and what hangs on it, drops when `from` is the cheaper way).
HNode* Lacam::step_to(HNode* from, const Vertex* C, Clock::time_point deadline)
{
  const uint64_t hash = config_hash(C, n_);
  HNode* h = explored_.find(C, hash);
  if (h) {
    link(from, h);
    rewrite(from, h, deadline);
    return h;
  }
  h = new_node(C, from, hash);
  h->g = from->g + edge_cost(from->C, h->C);
  h->h = heuristic(h->C);
  link(from, h);
  explored_.insert(h);
  return h;
}

// SUO from the configuration `lead` steps ahead on the best path (the root without one).
void Lacam::start_scatter(int lead)
{
  scatter_root_ = root_;
  if (goal_ && lead > 0) {
    std::vector<HNode*> p;
    for (HNode* h = goal_; h; h = h->parent) p.push_back(h);
    scatter_root_ = p[p.size() - 1 - std::min<size_t>(lead, p.size() - 1)];
  }
  scatter_.reset(Config(scatter_root_->C, scatter_root_->C + n_), opt_.scatter_margin, opt_.seed + 3,
                 opt_.scatter_max_passes);
  scatter_started_ = true;
  scatter_reroots0_ = reroots_;
  scatter_lead_ = steps_ahead(scatter_root_);
  guide_spent_ = 0;
}

// SUO work until the deadline or the budget left; charged work / N expansions. Returns false
// (nothing done) once SUO is finished or off. The lead is checked once, when an eighth of
// the agents of the first pass is done: if the agents moved m steps meanwhile, the pass
// needs about 8m, and when that is more than the steps left to SUO's start, SUO restarts
// 1.25 x 8m + 2 steps ahead (an eighth of a pass lost, instead of a dive from a
// configuration the agents have passed).
bool Lacam::scatter_step()
{
  if (!opt_.scatter && !opt_.scatter_first) return false;
  // A timed step of SUO's restart model (SUO's first start, the lead probe): it runs only when
  // its learnt cost fits what is left of the call, else the call stalls to a later one. Prior:
  // SUO's reset (O(|V|) + the paths' cells) and the probe's O(N log depth), about two
  // expansions (measured: 0.59-0.69 ms at warehouse-20-40-10-2-2 N = 1000).
  const auto restart_step = [this](auto&& step) {
    restart_cost_.set_prior(2 * expand_cost_.rate());
    if (!fits(restart_cost_.predict_ms(1))) {
      restart_cost_.forget();
      stalled_ = true;  // in a later call
      return;
    }
    const double c0 = thread_cpu_ms();
    step();
    restart_cost_.record(1, thread_cpu_ms() - c0);
  };
  if (!scatter_started_) {
    // Timed, the first start is a step of its own, when its cost fits (the restart's model:
    // both are SUO's reset, the first one also builds the occupancy lists, O(|V|) fresh
    // memory); it had shared a call with a slice that ran to the call's deadline.
    // The O(|V|) build on fresh memory goes first, in slices to the call's deadline (as one
    // step inside the start it cost 1.1 ms at warehouse-20-40-10-2-2 N = 1000).
    if (timed_ && opt_.scatter_prepare && !scatter_.prepared()) {
      if (!scatter_.prepare(deadline_)) stalled_ = true;  // the rest in a later call
      return true;
    }
    if (timed_) {
      restart_step([&] { start_scatter(opt_.scatter_lead); });
      return true;
    }
    start_scatter(opt_.scatter_lead);
  }
  if (scatter_.done()) {
    if (scatter_.ready()) pibt_.set_scatter(&scatter_);
    return false;
  }
  // Timed, the lead probe is a step of its own at the start of a call, when its cost (with
  // SUO's restart) fits: run after the slice, at its deadline, it overran 1 ms iterations by
  // 0.2-0.3 ms (warehouse-10-20-10-2-1 N = 600). The pass waits for it: a pass that went on
  // past the probe's point kept the lead at 30 and cost 10 % SOC at warehouse-20-40-10-2-2
  // N = 1000 (the first start's cost, which builds the occupancy lists, is not a restart's).
  // Untimed runs probe after the slice, as before (the same runs).
  if (timed_ && lead_probe_due()) {
    restart_step([&] { lead_probe(); });
    return true;
  }
  const uint64_t n = static_cast<uint64_t>(std::max(n_, 1));
  const uint64_t max_work = left_ >= UINT64_MAX / n ? UINT64_MAX : left_ * n;
  // Timed, a complete pass is published by its own slices, resumable like the A*s (untimed
  // runs publish at once, as before: the same runs).
  const uint64_t w0 = scatter_.pass_complete() ? scatter_.work() : 0;  // publish() adds to it
  if (scatter_.pass_complete()) scatter_.publish(deadline_);
  else scatter_.step(deadline_, max_work, !timed_);
  units_ = std::max<uint64_t>(1, (scatter_.work() - w0) / n);
  if (scatter_.ready()) pibt_.set_scatter(&scatter_);
  if (!timed_ && lead_probe_due()) lead_probe();
  return true;
}

bool Lacam::lead_probe_due() const
{
  return !scatter_probed_ && goal_ && scatter_.passes() == 0 && scatter_.planned() >= std::max(1, n_ / 8);
}

// The lead check of scatter_step (above), and SUO's restart further ahead when it is short.
void Lacam::lead_probe()
{
  scatter_probed_ = true;
  const uint64_t n = static_cast<uint64_t>(std::max(n_, 1));
  const uint64_t m = reroots_ - scatter_reroots0_;
  const uint64_t passes = static_cast<uint64_t>(std::max(1, opt_.scatter_dive_passes));
  const double suo = static_cast<double>(m * n * passes) / scatter_.planned();  // moves, from here
  if (!opt_.scatter_lead_dive || m == 0 || guide_spent_ <= 0) {
    const int need = static_cast<int>(suo * 5 / 4) + 2;
    if (m > 0 && need > steps_ahead(scatter_root_)) start_scatter(need);
    return;
  }
  // The guided dive must land before the agents reach its start too: it takes a PIBT call
  // per step of the path's rest from there, at the guide work per move measured so far.
  // SUO from further ahead is cheaper: its A*s are about as long as the agents' distances
  // left, so its passes scale with their sum there. The lead is the least L that covers
  // both from the node L steps ahead (binary search; the condition only loosens with L).
  std::vector<const HNode*> p;  // the best path, the root first
  for (const HNode* h = goal_; h; h = h->parent) p.push_back(h);
  std::reverse(p.begin(), p.end());
  const int depth = static_cast<int>(p.size()) - 1;
  const auto left = [&](const HNode* h) {
    int64_t d = 0;
    for (int i = 0; i < n_; ++i) d += dist_.get(i, h->C[i]);
    return static_cast<double>(std::max<int64_t>(d, 1));
  };
  const double here = left(scatter_root_);
  // A guided dive step is a guided PIBT call plus step_to: its learnt cost once a dive ran,
  // else kGuidedPrior x an expansion (scatter_lead_guided; off: an unguided expansion's cost,
  // 2-8x too cheap, so the lead came out short).
  const double step = !timed_                   ? 1.0
                      : !opt_.scatter_lead_guided ? expand_cost_.predict_ms(1)
                      : dive_cost_.samples() > 0  ? std::max(expand_cost_.predict_ms(1), dive_cost_.predict_ms(1))
                                                  : kGuidedPrior * expand_cost_.predict_ms(1);
  const double per_move = guide_spent_ / static_cast<double>(m);
  const auto covered = [&](int L) {
    const double moves = suo * left(p[L]) / here + (depth - L) * step / per_move;
    return L >= static_cast<int>(moves * 5 / 4) + 2;
  };
  const int now = std::max(0, steps_ahead(scatter_root_));
  if (now >= depth || covered(now)) return;
  int lo = now, hi = depth;  // covered(hi) or hi == depth
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (covered(mid) ? hi : lo) = mid;
  }
  start_scatter(hi);
}

int Lacam::steps_ahead(const HNode* x) const
{
  int k = -1, depth = 0;
  for (const HNode* h = goal_; h; h = h->parent, ++depth)
    if (h == x) k = depth;
  return k < 0 ? -1 : depth - 1 - k;
}

// Order: finish a running dive; after every newly published SUO pass, a guided dive from
// the node SUO started at, while that node is still ahead on the best path (the agents'
// vertices there are the scatter paths' starts, so every agent is guided from its first
// step; from the root once they are past it); more SUO passes, as long as these dives
// win; then (LacamOptions::dive) guided dives from the root.
void Lacam::guide_step()
{
  ++expansions_;
  if (dive_) {
    dive_step();
    return;
  }
  if (opt_.scatter && !scatter_stopped_) {
    if (scatter_started_ && scatter_.passes() > passes_dived_ &&
        (scatter_.passes() >= opt_.scatter_dive_passes || scatter_.done())) {
      passes_dived_ = scatter_.passes();
      if (scatter_.ready()) {  // from the root when the agents are past SUO's start already
        start_dive(steps_ahead(scatter_root_) >= 0 ? scatter_root_ : root_);
        guided_dive_ = true;
        dive_step();
        return;
      }
    }
    if (scatter_step()) return;
  }
  if (opt_.dive) {
    start_dive(root_);
    dive_step();
  }
}

void Lacam::start_dive(HNode* from)
{
  dive_ = from;
  dive_ahead_ = steps_ahead(from);
  dive_reroots0_ = reroots_;
  dive_len_ = 0;
  int depth = 0;
  for (const HNode* h = goal_; h && h != root_; h = h->parent) ++depth;
  dive_limit_ = 2 * depth + 16;
  // A scatter path may be up to scatter_margin longer than a shortest one.
  dive_guided_len_ = std::max(1, depth - std::max(0, steps_ahead(from)) + opt_.scatter_margin);
  if (!opt_.scatter_dive_guard) dive_guided_len_ = dive_limit_;
}

// Continues the running dive by PIBT steps until it reaches the goals, fails, or the
// deadline / budget ends the call; one step is one expansion's work.
void Lacam::dive_step()
{
  uint64_t steps = 0;
  const auto end = [&](bool won) {
    // A guided dive that does not beat the best path: SUO does not pay here, its share of
    // the budget goes back to LNS and LaCAM* (no more passes; PIBT keeps the guidance).
    if (guided_dive_ && !won) scatter_stopped_ = true;
    if (guided_dive_ && dive_ahead_ > 0 && reroots_ - dive_reroots0_ > static_cast<uint64_t>(dive_ahead_)) ++late_dives_;
    guided_dive_ = false;
    dive_ = nullptr;
    first_dive_done_ = true;
    ++dives_;
    dive_wins_ += won;
    dive_failures_ = won ? 0 : dive_failures_ + 1;
  };
  while (dive_) {
    if (dive_len_ >= dive_limit_) {
      ++dive_stalls_;
      end(false);
      break;
    }
    ++steps;
    // Scatter paths can livelock a rollout (measured: 10 agents off their goals after 3000
    // steps); past the length of the path it must beat (+ the margin), PIBT goes on by
    // distances alone.
    const Scatter* guide = pibt_.scatter();
    if (dive_len_ >= dive_guided_len_) pibt_.set_scatter(nullptr);
    const double q0 = timed_ ? thread_cpu_ms() : 0.0;
    bool ok;
    if (timed_ && opt_.dive_pause) {
      // Resumable (LacamOptions::dive_pause): the PIBT call stops at the call's deadline and
      // goes on in the next guide step, the same generation (nothing else uses pibt_
      // meanwhile: refine_expand keeps the guide's turn while a dive step is paused).
      if (!dive_paused_ || !pibt_.pending()) pibt_.start(dive_->C, dive_->order, nullptr), dive_part_ms_ = 0;
      const Pibt::Gen r = pibt_.resume(rng_, deadline_);
      pibt_.set_scatter(guide);
      dive_paused_ = r == Pibt::Gen::paused;
      if (dive_paused_) {
        dive_part_ms_ += thread_cpu_ms() - q0;
        ++dive_pauses_;
        break;
      }
      ok = r == Pibt::Gen::done;
      if (ok) std::copy(pibt_.result(), pibt_.result() + n_, scratch_.begin());
    } else {
      ok = pibt_.generate(dive_->C, dive_->order, nullptr, scratch_.data(), rng_);
      pibt_.set_scatter(guide);
    }
    if (!ok) {
      end(false);
      break;
    }
    const int64_t g_goal = goal_->g;
    // The rewiring after a known node stops at the deadline too (0.43 ms once at
    // warehouse-20-40-10-2-2 N = 1000); the win test below reads the goal's g, which the
    // rewiring's first node (the link from dive_) sets.
    dive_ = step_to(dive_, scratch_.data(), timed_ && opt_.dive_pause ? deadline_ : Clock::time_point::max());
    if (timed_) dive_cost_.record(1, thread_cpu_ms() - q0 + dive_part_ms_), dive_part_ms_ = 0;
    ++dive_len_;
    if (dive_ == goal_) {
      end(goal_->g < g_goal);
      break;
    }
    if (steps >= left_ || (timed_ && !fits(dive_cost_.predict_ms(1)))) break;
  }
  units_ = std::max<uint64_t>(1, steps);
}

}  // namespace planner

