#include "planner/rotation/rotation_pibt.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "planner/priority_hint.hpp"

namespace planner {

RotationPibt::RotationPibt(const Graph& g, const Config& starts, const Config& goals, uint64_t seed, GoalTest test,
                           int heading)
    : g_(g), dist_(g), rng_(seed), current_(starts), heading_(starts.size(), heading)
{
  if (heading < 0 || heading > 3) throw std::invalid_argument("heading must be 0..3");
  const size_t n = starts.size();
  if (goals.size() != n) throw std::invalid_argument("starts and goals differ in size");
  occ_now_.assign(static_cast<size_t>(g.size()), -1);
  occ_next_.assign(static_cast<size_t>(g.size()), -1);
  for (size_t i = 0; i < n; ++i) {
    if (starts[i] < 0 || starts[i] >= g.size()) throw std::invalid_argument("start of agent " + std::to_string(i) + " not in the graph");
    if (occ_now_[starts[i]] >= 0) throw std::invalid_argument("agents " + std::to_string(occ_now_[starts[i]]) + " and " + std::to_string(i) + " start on one cell");
    occ_now_[starts[i]] = static_cast<int32_t>(i);
  }
  wait_cost_ = std::min<uint32_t>(dist_.turn_cost(), dist_.guidance().min_forward());  // move costs alone: rotation_dist.hpp
  goal_table_.assign(n, nullptr);
  prio_.assign(n, 0.0);
  set_goals(goals, std::move(test));
  order_.resize(n);
  for (size_t i = 0; i < n; ++i) order_[i] = static_cast<int32_t>(i);
  next_ = current_;
}

void RotationPibt::set_headings(const std::vector<int>& headings)
{
  if (headings.size() != heading_.size()) throw std::invalid_argument("headings: wrong number of robots");
  for (int h : headings)
    if (h < 0 || h > 3) throw std::invalid_argument("heading must be 0..3");
  heading_ = headings;
  planned_ = false;  // a step planned for the old headings is void
}

void RotationPibt::set_goals(const Config& goals, GoalTest test)
{
  if (goals.size() != current_.size()) throw std::invalid_argument("goals: wrong number of agents");
  for (size_t i = 0; i < goals.size(); ++i) {
    if (goals[i] < 0 || goals[i] >= g_.size()) throw std::invalid_argument("goal of agent " + std::to_string(i) + " not in the graph");
    if (goal_table_[i] && goals_[i] == goals[i]) continue;
    if (goal_table_[i]) dist_.unpin(goal_table_[i]);
    goal_table_[i] = dist_.table(goals[i]);
    dist_.pin(goal_table_[i]);
    // A new goal: its waiting time starts again; the distance breaks ties (far first).
    prio_[i] = static_cast<double>(h(static_cast<int>(i))) / 65536.0;
  }
  // The task layer's hints (RealtimePlanner::set_priority_hint): a floor over the tie part
  // (planner/priority_hint.hpp), as the LaCAM family's raise_to_hint.
  if (hint_.size() == goals.size())
    for (size_t i = 0; i < goals.size(); ++i)
      prio_[i] = hint_floor(prio_[i], prio_[i] - static_cast<double>(static_cast<long>(prio_[i])), hint_[i]);
  goals_ = goals;
  test_ = std::move(test);
  dist_.trim();
  planned_ = false;
}

void RotationPibt::set_pockets(std::vector<Vertex> pocket, float cost)
{
  if (!pocket.empty() && pocket.size() != static_cast<size_t>(g_.size())) throw std::invalid_argument("pockets: one label per vertex");
  exit_.set(g_, pocket);
  pocket_ = std::move(pocket);
  // `cost` moves, in the distances' costs (a forward move costs at least min_forward()).
  pocket_cost_ = cost > 0 ? static_cast<uint32_t>(std::lround(cost * dist_.guidance().min_forward())) : 0;
  planned_ = false;
}

void RotationPibt::set_guidance(Guidance gd)
{
  dist_.set_guidance(std::move(gd));
  wait_cost_ = std::min<uint32_t>(dist_.turn_cost(), dist_.guidance().min_forward());
  std::fill(goal_table_.begin(), goal_table_.end(), nullptr);  // dropped: take them anew
  const Config goals = goals_;
  set_goals(goals, test_);
}

Status RotationPibt::search(const Budget&)
{
  if (planned_) return at_goal() ? Status::Solved : Status::Searching;
  const int n = static_cast<int>(current_.size());
  // Priorities changed at the last commit and at goal changes. Insertion sort: the order
  // changes little per step.
  auto before = [this](int32_t x, int32_t y) { return prio_[x] > prio_[y] || (prio_[x] == prio_[y] && x < y); };
  for (int k = 1; k < n; ++k) {
    const int32_t x = order_[k];
    int j = k;
    for (; j > 0 && before(x, order_[j - 1]); --j) order_[j] = order_[j - 1];
    order_[j] = x;
  }
  action_.assign(static_cast<size_t>(n), 'W');
  decided_.assign(static_cast<size_t>(n), -1);
  memo_.assign(static_cast<size_t>(n), 0);
  if (target_.size() != static_cast<size_t>(n)) target_.assign(static_cast<size_t>(n), -1), blocked_.assign(static_cast<size_t>(n), 0);
  if (pocket_exit_) exit_.mark(current_, goals_);
  const bool exit_rule = pocket_exit_ && exit_.any();
  // A robot still turning toward the cell it chose keeps it: PIBT does not replan it, and
  // the cell stays reserved (the start kit's causal PIBT). Facing it, it is planned anew.
  for (int i = 0; i < n; ++i) {
    const Vertex c = target_[i];
    const bool facing = dist_.ahead(current_[i], heading_[i]) == c;
    if (c < 0 || c == current_[i] || (facing && blocked_[i] > kPatience) || occ_next_[c] >= 0 ||
        (exit_rule && exit_.blocks(current_[i], c))) {
      target_[i] = -1;
      blocked_[i] = 0;
      continue;
    }
    decided_[i] = c;
    occ_next_[c] = i;
  }
  if (exit_rule) {
    // Leavers first (PocketExit::first): a robot that must get out of a pocket whose way out
    // is taken plans before everyone else, so it pushes the robots waiting at the mouth aside
    // (a quarter turn) rather than waiting for them; they age while it waits, and a leaver's
    // priority restarted with its new goal.
    for (int32_t i : order_)
      if (decided_[i] < 0 && exit_.first(current_[i], goals_[i])) pibt(i, -1);
  }
  for (int32_t i : order_)
    if (decided_[i] < 0) pibt(i, -1);
  for (int i = 0; i < n; ++i) {
    const Vertex v = current_[i], c = decided_[i];
    if (c == v) continue;
    const int o = heading_[i];
    int d = 0;
    while (dist_.ahead(v, d) != c) ++d;
    action_[i] = d == o ? 'F' : turn_toward(o, d);
  }
  next_ = current_;
  for (int i = 0; i < n; ++i) {
    if (moves(i)) next_[i] = decided_[i];
    else if (action_[i] == 'F') action_[i] = 'W', ++blocked_[i];  // blocked: waits, facing its cell
  }
  for (int i = 0; i < n; ++i) {
    target_[i] = decided_[i] != current_[i] ? decided_[i] : -1;
    occ_next_[decided_[i]] = -1;  // every reservation is someone's decided cell
  }
  planned_ = true;
  ++steps_planned_;
  return at_goal() ? Status::Solved : Status::Searching;
}

bool RotationPibt::pibt(int i, int asker)
{
  struct Cand {
    Vertex c;
    uint32_t cost, tie;
  };
  const Vertex v = current_[i];
  const int o = heading_[i];
  RotationDist::Table* t = goal_table_[i];
  Cand cand[5];
  int m = 0;
  for (int d = 0; d < 4; ++d) {
    const Vertex c = dist_.ahead(v, d);
    if (c < 0) continue;
    if (pocket_exit_ && exit_.blocks(v, c)) continue;  // deeper into a pocket a robot must leave
    const uint32_t turns = static_cast<uint32_t>(quarter_turns(o, d));
    // In the distances' costs (guidance.hpp; 1 per action without guidance).
    uint32_t cost = turns * dist_.turn_cost() + dist_.forward_cost(v, d) + dist_.get(t, c, d);
    if (asker >= 0 && back_last_ && turns == 2) cost += 1u << 16;  // asked to vacate: the cell behind last
    if (pocket_cost_ > 0 && !pocket_.empty()) {
      const Vertex p = pocket_[c];
      if (p >= 0 && p != pocket_[v] && p != pocket_[goals_[i]]) cost += pocket_cost_;  // a foreign pocket
    }
    cand[m++] = {c, cost, d == o ? 0u : 1 + (static_cast<uint32_t>(rng_.next()) >> 1)};
  }
  if (asker < 0) cand[m++] = {v, wait_cost_ + dist_.get(t, v, o), 1 + (static_cast<uint32_t>(rng_.next()) >> 1)};
  // Insertion sort of at most 5: the order std::sort gives below 16 elements (its final
  // insertion sort), without GCC 12's false -Warray-bounds on a fixed array.
  for (int a = 1; a < m; ++a)
    for (int b = a; b > 0 && (cand[b].cost != cand[b - 1].cost ? cand[b].cost < cand[b - 1].cost : cand[b].tie < cand[b - 1].tie); --b)
      std::swap(cand[b], cand[b - 1]);
  for (int k = 0; k < m; ++k) {
    const Vertex c = cand[k].c;
    if (occ_next_[c] >= 0) continue;                   // reserved
    if (asker >= 0 && c == current_[asker]) continue;  // swap with the asker
    const int j = c != v ? occ_now_[c] : -1;
    if (j >= 0 && decided_[j] == v) continue;          // j is coming to i's cell: swap
    occ_next_[c] = i;
    decided_[i] = c;
    if (j >= 0 && decided_[j] < 0 && !pibt(j, i)) {
      decided_[i] = -1;  // j stays: occ_next_[c] is j's now
      continue;
    }
    return true;
  }
  decided_[i] = v;  // stays (a robot turning toward v waits for it: moves())
  if (occ_next_[v] < 0) occ_next_[v] = i;
  return false;
}

bool RotationPibt::moves(int i)
{
  enum { Unknown = 0, Visiting, Yes, No };
  if (action_[i] != 'F') return false;
  if (memo_[i] == Visiting) return true;  // a cycle of robots moving forward: all go together
  if (memo_[i] != Unknown) return memo_[i] == Yes;
  memo_[i] = Visiting;
  const Vertex c = decided_[i];
  const int j = occ_now_[c];
  // The cell ahead must be free, or its robot must leave it forward now, and not into i's cell.
  const bool ok = j < 0 || (decided_[j] != current_[i] && moves(j));
  memo_[i] = ok ? Yes : No;
  return ok;
}

const Config& RotationPibt::next()
{
  if (!planned_) search(Budget{});
  return next_;
}

void RotationPibt::commit()
{
  if (!planned_) search(Budget{});
  const int n = static_cast<int>(current_.size());
  for (int i = 0; i < n; ++i) occ_now_[current_[i]] = -1;
  for (int i = 0; i < n; ++i) {
    current_[i] = next_[i];
    occ_now_[current_[i]] = i;
    heading_[i] = heading_after(heading_[i], action_[i]);
    // PIBT's dynamic priority: +1 per step away from the goal, its tie part on it.
    prio_[i] = current_[i] != goals_[i] ? prio_[i] + 1.0 : prio_[i] - static_cast<double>(static_cast<long>(prio_[i]));
    // A robot in a dead end blocks its only way out: it goes first (the start kit's boost).
    if (current_[i] != goals_[i] && g_.degree(current_[i]) == 1) prio_[i] += kDeadEndBoost;
  }
  planned_ = false;
}

}  // namespace planner

namespace planner {

RotationPibt::Snapshot RotationPibt::snapshot() const
{
  return {current_, heading_, prio_, order_, target_, blocked_, rng_, steps_planned_};
}

void RotationPibt::restore(const Snapshot& s)
{
  for (Vertex v : current_) occ_now_[v] = -1;
  current_ = s.current;
  for (size_t i = 0; i < current_.size(); ++i) occ_now_[current_[i]] = static_cast<int32_t>(i);
  heading_ = s.heading;
  prio_ = s.prio;
  order_ = s.order;
  target_ = s.target;
  blocked_ = s.blocked;
  rng_ = s.rng;
  steps_planned_ = s.steps_planned;
  next_ = current_;
  planned_ = false;
}

void RotationPibt::commit_actions(const std::string& actions)
{
  if (!planned_) search(Budget{});
  if (actions.size() != current_.size()) throw std::invalid_argument("commit_actions: wrong number of actions");
  for (size_t i = 0; i < current_.size(); ++i) {
    if (actions[i] != action_[i]) target_[i] = -1, blocked_[i] = 0;  // the cell it turned toward is no longer its plan
    next_[i] = actions[i] == 'F' ? dist_.ahead(current_[i], heading_[i]) : current_[i];
  }
  action_ = actions;
  commit();
}

}  // namespace planner
