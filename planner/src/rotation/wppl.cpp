#include "planner/rotation/wppl.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace planner {

namespace {

// The action from s to t: F (another cell: the one ahead), R, C or W.
char action_between(const RotState& s, const RotState& t)
{
  if (t.v != s.v) return 'F';
  if (t.o == turned_cw(s.o)) return 'R';
  if (t.o == turned_ccw(s.o)) return 'C';
  return 'W';
}

// Without any limit a step would search forever: this many LNS iterations then.
constexpr uint64_t kUnlimitedIters = 1000;

}  // namespace

Wppl::Wppl(const Graph& g, const Config& starts, const Config& goals, uint64_t seed, GoalTest test, int heading,
           WpplOptions opt)
    : g_(g), pibt_(g, starts, goals, seed, std::move(test), heading), rng_(seed ^ 0x5eedull), astar_(pibt_.dist())
{
  set_options(opt);
}

void Wppl::set_options(const WpplOptions& opt)
{
  if (opt.window < 1) throw std::invalid_argument("wppl: window must be at least 1");
  if (opt.neighbourhood < 1) throw std::invalid_argument("wppl: neighbourhood must be at least 1");
  if (opt.window != opt_.window) tail_valid_ = false;
  opt_ = opt;
  if (!opt_.reuse_tail) tail_valid_ = false;
  planned_ = false;
}

void Wppl::set_headings(const std::vector<int>& headings)
{
  pibt_.set_headings(headings);
  planned_ = false;  // the window was rolled out from the old headings
  tail_valid_ = false;
}

void Wppl::set_goals(const Config& goals, GoalTest test)
{
  pibt_.set_goals(goals, std::move(test));
  planned_ = false;  // the costs change; the last plan's tail stays conflict-free
}

void Wppl::initial_plan()
{
  const int n = static_cast<int>(current().size());
  const int w = opt_.window;
  plan_.assign(static_cast<size_t>(n), RotPath(static_cast<size_t>(w) + 1));
  // PIBT rolled forward w steps, then put back.
  const RotationPibt::Snapshot snap = pibt_.snapshot();
  for (int t = 0; t <= w; ++t) {
    if (t > 0) {
      pibt_.search(Budget{});
      pibt_.commit();
    }
    for (int i = 0; i < n; ++i) plan_[i][t] = {pibt_.current()[i], pibt_.headings()[i]};
  }
  pibt_.restore(snap);
  cost_.resize(static_cast<size_t>(n));
  objective_ = 0;
  for (int i = 0; i < n; ++i) objective_ += cost_[i] = cost(i);
  if (tail_valid_ && tail_.size() == plan_.size()) {
    // The last plan's tail (W states from t = 1) gets its last step from PIBT, one step
    // from the tail's end states (WPPL extends its previous plan the same way).
    RotationPibt::Snapshot end = snap;
    for (int i = 0; i < n; ++i) end.current[i] = tail_[i].back().v, end.heading[i] = tail_[i].back().o;
    std::fill(end.target.begin(), end.target.end(), -1);
    std::fill(end.blocked.begin(), end.blocked.end(), 0);
    pibt_.restore(end);
    pibt_.search(Budget{});
    pibt_.commit();
    for (int i = 0; i < n; ++i) tail_[i].push_back({pibt_.current()[i], pibt_.headings()[i]});
    pibt_.restore(snap);
    int64_t tail_obj = 0;
    for (int i = 0; i < n; ++i)
      tail_obj += windowed_cost(pibt_.dist(), pibt_.goal_table(i), goals()[i], tail_[i]) + pocket_penalty(i, tail_[i]);
    if (tail_obj < objective_) {
      plan_.swap(tail_);
      for (int i = 0; i < n; ++i) cost_[i] = cost(i);
      objective_ = tail_obj;
      ++tail_starts_;
    }
  }
  res_.reset(g_.size(), w);
  for (int i = 0; i < n; ++i) res_.add(i, plan_[i]);
  h0_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) h0_[i] = pibt_.dist().get(pibt_.goal_table(i), plan_[i][0].v, plan_[i][0].o);
  initial_objective_ = objective_;
  in_nb_.resize(static_cast<size_t>(n), 0);
}

void Wppl::neighbourhood(std::vector<int>& nb)
{
  nb.clear();
  const int n = static_cast<int>(plan_.size());
  const RotationDist& d = pibt_.dist();
  // Delayed robots: their windowed cost exceeds their distance (others are in the way).
  std::vector<int>& delayed = delayed_;
  delayed.clear();
  for (int i = 0; i < n; ++i)
    if (h0_[i] < RotationDist::kFar && cost_[i] > h0_[i]) delayed.push_back(i);
  if (delayed.empty()) return;
  const int a = delayed[rng_.below(static_cast<uint32_t>(delayed.size()))];
  if (++nb_stamp_ == 0) std::fill(in_nb_.begin(), in_nb_.end(), 0), nb_stamp_ = 1;
  nb.push_back(a);
  in_nb_[a] = nb_stamp_;
  // Its ideal route: the descent of h from its state, ignoring the others.
  RotationDist::Table* t = pibt_.goal_table(a);
  const Vertex goal = goals()[a];
  RotState s = plan_[a][0];
  std::vector<int>& cand = cand_;
  cand.clear();
  const int w = opt_.window;
  Vertex scanned = -1;
  for (int k = 0; k <= w; ++k) {
    if (s.v != scanned)  // a turn keeps the cell: scanned already
      for (int tt = 0; tt <= w; ++tt) {
        const int b = res_.at(s.v, tt);
        if (b >= 0 && in_nb_[b] != nb_stamp_) in_nb_[b] = nb_stamp_, cand.push_back(b);
      }
    scanned = s.v;
    if (s.v == goal) break;
    RotState best{s.v, turned_cw(s.o)};
    uint32_t best_h = d.get(t, best.v, best.o);
    const RotState ccw{s.v, turned_ccw(s.o)};
    if (const uint32_t hc = d.get(t, ccw.v, ccw.o); hc < best_h) best = ccw, best_h = hc;
    const Vertex u = d.ahead(s.v, s.o);
    if (u >= 0)
      if (const uint32_t hf = d.get(t, u, s.o); hf <= best_h) best = {u, s.o}, best_h = hf;
    s = best;
  }
  rng_.shuffle(cand.data(), static_cast<int>(cand.size()));
  for (int b : cand) {
    if (static_cast<int>(nb.size()) >= opt_.neighbourhood) break;
    nb.push_back(b);
  }
}

void Wppl::set_pockets(std::vector<Vertex> pocket, float cost)
{
  pibt_.set_pockets(pocket, cost);  // checks the labels
  pocket_ = std::move(pocket);
  pocket_cost_ = cost > 0 ? std::lround(cost * pibt_.dist().guidance().min_forward()) : 0;
  planned_ = false;
}

int64_t Wppl::pocket_penalty(int i, const RotPath& p) const
{
  if (pocket_cost_ == 0 || pocket_.empty()) return 0;
  const Vertex mine = pocket_[goals()[i]];
  for (size_t t = 1; t < p.size(); ++t) {
    const Vertex q = pocket_[p[t].v];
    if (q >= 0 && q != pocket_[p[t - 1].v] && q != mine) return pocket_cost_;
  }
  return 0;
}

bool Wppl::lns_iteration(Clock::time_point deadline)
{
  std::vector<int>& nb = nb_;
  neighbourhood(nb);
  if (nb.empty()) return false;
  rng_.shuffle(nb.data(), static_cast<int>(nb.size()));  // the order of prioritized planning
  int64_t old_sum = 0;
  for (int i : nb) old_sum += cost_[i], res_.remove(i, plan_[i]);
  std::vector<RotPath>& paths = paths_;
  std::vector<int64_t>& costs = costs_;
  if (paths.size() < nb.size()) paths.resize(nb.size());
  costs.resize(nb.size());
  size_t k = 0;
  int64_t new_sum = 0;
  for (; k < nb.size(); ++k) {
    const int i = nb[k];
    costs[k] = astar_.plan(plan_[i][0], goals()[i], pibt_.goal_table(i), res_, paths[k], deadline);
    if (costs[k] < 0) break;
    costs[k] += pocket_penalty(i, paths[k]);
    res_.add(i, paths[k]);
    new_sum += costs[k];
  }
  // Equal cost is accepted too (a sideways move): the search drifts across the plateaus
  // of the windowed objective instead of stopping at the first plan it cannot better.
  bool accept = k == nb.size() && (new_sum < old_sum || (opt_.accept_ties && new_sum == old_sum));
  if (accept && opt_.pareto)  // nobody worse off: PIBT's precedence (who pushed whom) stands
    for (size_t j = 0; j < nb.size(); ++j) accept &= costs[j] <= cost_[nb[j]];
  for (size_t j = 0; j < k; ++j) res_.remove(nb[j], paths[j]);
  for (size_t j = 0; j < nb.size(); ++j) {
    const int i = nb[j];
    if (accept) plan_[i].swap(paths[j]), cost_[i] = costs[j];
    res_.add(i, plan_[i]);
  }
  if (accept) objective_ += new_sum - old_sum, ++accepted_, sideways_ += new_sum == old_sum;
  return true;
}

Status Wppl::search(const Budget& b)
{
  const auto deadline = b.deadline_from(Clock::now());
  if (!planned_) {
    initial_plan();
    planned_ = true;
    iters_step_ = 0;
    ++steps_;
  }
  uint64_t limit = b.expansions;
  if (opt_.max_iters > 0) limit = std::min(limit, opt_.max_iters - std::min(opt_.max_iters, iters_step_));
  if (deadline == Clock::time_point::max()) limit = std::min(limit, kUnlimitedIters);
  for (uint64_t k = 0; k < limit && Clock::now() < deadline; ++k) {
    if (!lns_iteration(deadline)) break;  // nobody is delayed
    ++iters_, ++iters_step_;
  }
  const int n = static_cast<int>(plan_.size());
  next_.resize(static_cast<size_t>(n));
  action_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    next_[i] = plan_[i][1].v;
    action_[i] = action_between(plan_[i][0], plan_[i][1]);
  }
  return at_goal() ? Status::Solved : Status::Searching;
}

const Config& Wppl::next()
{
  if (!planned_) search(Budget::expansion_count(0));
  return next_;
}

void Wppl::commit()
{
  if (!planned_) search(Budget::expansion_count(0));
  pibt_.search(Budget{});  // the step the rollout started with (same state, same draws)
  pibt_.commit_actions(action_);
  if (opt_.reuse_tail) {
    // The refined plan one step on (its last step comes from PIBT in initial_plan()).
    tail_.resize(plan_.size());
    for (size_t i = 0; i < plan_.size(); ++i) tail_[i].assign(plan_[i].begin() + 1, plan_[i].end());
    tail_valid_ = true;
  }
  planned_ = false;
}

}  // namespace planner
