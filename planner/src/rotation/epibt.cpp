#include "planner/rotation/epibt.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace planner {

Epibt::Epibt(const Graph& g, const Config& starts, const Config& goals, Options opt, GoalTest test, int heading)
    : g_(g), dist_(g), current_(starts), heading_(starts.size(), heading)
{
  if (heading < 0 || heading > 3) throw std::invalid_argument("heading must be 0..3");
  const size_t n = starts.size();
  if (goals.size() != n) throw std::invalid_argument("starts and goals differ in size");
  std::vector<char> seen(static_cast<size_t>(g.size()), 0);
  for (size_t i = 0; i < n; ++i) {
    if (starts[i] < 0 || starts[i] >= g.size()) throw std::invalid_argument("start of agent " + std::to_string(i) + " not in the graph");
    if (seen[starts[i]]) throw std::invalid_argument("agent " + std::to_string(i) + " starts on another agent's cell");
    seen[starts[i]] = 1;
  }
  // Move costs alone (slow lanes, rotation_dist.hpp) make the costs non-uniform too.
  guided_ = !dist_.guidance().uniform();
  wait_cost_ = std::min<uint32_t>(dist_.turn_cost(), dist_.guidance().min_forward());
  goal_table_.assign(n, nullptr);
  age_.assign(n, 0.0);
  key_.assign(n, 0.0);
  set_goals(goals, std::move(test));
  order_.resize(n);
  ncand_.assign(n, 0);
  cand_stamp_.assign(n, 0);
  visited_.assign(n, 0);
  placed_.assign(n, 0);
  visits_.assign(n, 0);
  action_.assign(n, 'W');
  next_ = current_;
  set_options(opt);
}

void Epibt::set_headings(const std::vector<int>& headings)
{
  if (headings.size() != heading_.size()) throw std::invalid_argument("headings: wrong number of robots");
  for (int h : headings)
    if (h < 0 || h > 3) throw std::invalid_argument("heading must be 0..3");
  heading_ = headings;
  planned_ = false;  // a step planned for the old headings is void
  tf_reset();        // guide paths start from the robots' states
}

void Epibt::tf_reset()
{
  tf_.reset();
  tf_queue_.clear();
  const size_t n = current_.size();
  tf_queued_.assign(n, 0);
  tf_next_ = 0;
  if (!opt_.tf.on || !TrafficFlow::fits(n, g_.size(), opt_.tf)) return;
  tf_ = std::make_unique<TrafficFlow>(dist_, n, opt_.tf);
  for (size_t i = 0; i < n; ++i) tf_queue_.push_back(static_cast<int32_t>(i)), tf_queued_[i] = 1;
}

void Epibt::tf_work(Clock::time_point deadline)
{
  if (!tf_) return;
  const bool clock = deadline != Clock::time_point::max();
  while (!tf_queue_.empty() && !(clock && Clock::now() >= deadline)) {
    const int i = tf_queue_.front();
    tf_queue_.pop_front();
    tf_queued_[static_cast<size_t>(i)] = 0;
    tf_->plan(i, current_[i], heading_[i], goals_[i]);
    cand_stamp_[i] = 0;  // ranked anew
  }
  if (!tf_queue_.empty() || planned_) return;
  // Refresh: the oldest guide paths again under today's traffic (round robin).
  const size_t n = current_.size();
  for (int k = 0; k < opt_.tf.refresh && n > 0 && !(clock && Clock::now() >= deadline); ++k) {
    const int i = static_cast<int>(tf_next_++ % n);
    tf_->plan(i, current_[i], heading_[i], goals_[i]);
    cand_stamp_[i] = 0;
  }
}

bool Epibt::precompute(std::chrono::steady_clock::time_point deadline)
{
  if (tf_ && !tf_queue_.empty()) tf_work(deadline);
  return dist_.precompute(deadline) || !tf_queue_.empty();
}

void Epibt::set_guidance(Guidance gd)
{
  dist_.set_guidance(std::move(gd));
  guided_ = !dist_.guidance().uniform();
  wait_cost_ = std::min<uint32_t>(dist_.turn_cost(), dist_.guidance().min_forward());
  std::fill(goal_table_.begin(), goal_table_.end(), nullptr);  // dropped: take them anew
  const Config goals = goals_;
  set_goals(goals, test_);
  ++stamp_;  // candidates ranked by the old costs are stale
  if (tf_) tf_reset();  // guide tables in the old costs: all anew
}

void Epibt::set_pockets(std::vector<Vertex> pocket, float cost)
{
  if (!pocket.empty() && pocket.size() != static_cast<size_t>(g_.size())) throw std::invalid_argument("pockets: one label per vertex");
  pocket_ = std::move(pocket);
  pocket_moves_ = cost > 0 ? cost : 0;
  exit_.set(g_, pocket_);  // depths for the exit rule (pocket_exit)
}

bool Epibt::enters_blocked_pocket(int i, const Vertex* cells) const
{
  Vertex from = current_[i];
  for (int d = 0; d < opt_.depth; ++d) {
    if (exit_.blocks(from, cells[d])) return true;
    from = cells[d];
  }
  return false;
}

void Epibt::set_goals(const Config& goals, GoalTest test)
{
  if (goals.size() != current_.size()) throw std::invalid_argument("goals: wrong number of agents");
  for (size_t i = 0; i < goals.size(); ++i) {
    if (goals[i] < 0 || goals[i] >= g_.size()) throw std::invalid_argument("goal of agent " + std::to_string(i) + " not in the graph");
    if (goal_table_[i] && goals_[i] == goals[i]) continue;
    if (tf_) {  // a new goal: the old guide path leaves the flows, a new one is wanted
      tf_->drop(static_cast<int>(i));
      if (!tf_queued_[i]) tf_queue_.push_back(static_cast<int32_t>(i)), tf_queued_[i] = 1;
    }
    if (goal_table_[i]) dist_.unpin(goal_table_[i]);
    goal_table_[i] = dist_.table(goals[i]);
    dist_.pin(goal_table_[i]);
    age_[i] = static_cast<double>(h(static_cast<int>(i))) / 65536.0;  // a new goal: waiting starts again
  }
  goals_ = goals;
  test_ = std::move(test);
  dist_.trim();
  planned_ = false;
}

bool Epibt::walk(int i, int op, Vertex* cells, int32_t* edges, int* end_heading) const
{
  Vertex v = current_[i];
  int o = heading_[i];
  const std::string& a = ops_[static_cast<size_t>(op)].acts;
  for (size_t d = 0; d < a.size(); ++d) {
    int32_t e = -1;
    if (a[d] == 'F') {
      const Vertex u = dist_.ahead(v, o);
      if (u < 0) return false;
      // An undirected edge: its lower cell, and the axis (0: x, 1: y).
      e = (o == 0 || o == 1 ? v : u) * 2 + (o & 1);
      v = u;
    } else {
      o = heading_after(o, a[d]);
    }
    cells[d] = v;
    edges[d] = e;
  }
  if (end_heading) *end_heading = o;
  return true;
}

void Epibt::set_op(int i, int op)
{
  const size_t D = static_cast<size_t>(opt_.depth);
  op_[i] = op;
  if (!walk(i, op, &cells_[static_cast<size_t>(i) * D], &edges_[static_cast<size_t>(i) * D], nullptr))
    throw std::logic_error("epibt: agent " + std::to_string(i) + " holds an operation into a wall");
}

void Epibt::place(int i)
{
  const size_t D = static_cast<size_t>(opt_.depth);
  if (scoring_) score_ += gain(i);
  for (size_t d = 0; d < D; ++d) {
    int32_t& c = used_cell_[static_cast<size_t>(cells_[i * D + d]) * D + d];
    if (c >= 0) throw std::logic_error("epibt: agents " + std::to_string(c) + " and " + std::to_string(i) + " on one cell");
    c = i;
    if (edges_[i * D + d] >= 0) used_edge_[static_cast<size_t>(edges_[i * D + d]) * D + d] = i;
  }
}

void Epibt::unplace(int i)
{
  const size_t D = static_cast<size_t>(opt_.depth);
  if (scoring_) score_ -= gain(i);
  for (size_t d = 0; d < D; ++d) {
    used_cell_[static_cast<size_t>(cells_[i * D + d]) * D + d] = -1;
    if (edges_[i * D + d] >= 0) used_edge_[static_cast<size_t>(edges_[i * D + d]) * D + d] = -1;
  }
}

int Epibt::conflict(int i) const
{
  const size_t D = static_cast<size_t>(opt_.depth);
  int who = -1;
  auto meet = [&who](int32_t j) {
    if (j < 0 || j == who) return true;
    if (who >= 0) return false;
    who = j;
    return true;
  };
  for (size_t d = 0; d < D; ++d) {
    if (!meet(used_cell_[static_cast<size_t>(cells_[i * D + d]) * D + d])) return -2;
    if (edges_[i * D + d] >= 0 && !meet(used_edge_[static_cast<size_t>(edges_[i * D + d]) * D + d])) return -2;
  }
  return who;
}

void Epibt::candidates(int i)
{
  if (cand_stamp_[i] == stamp_) return;
  cand_stamp_[i] = stamp_;
  const int D = opt_.depth;
  const size_t m = ops_.size();
  const Vertex goal = goals_[i];
  const bool on_goal = current_[i] == goal;
  std::pair<uint32_t, uint8_t> c[256];
  int k = 0;
  Vertex cells[8];
  int32_t edges[8];
  // Foreign pockets: in the units of the guided costs (a forward move costs at least
  // min_forward(); 1 unguided), as RotationPibt charges them.
  const bool pockets = pocket_moves_ > 0 && !pocket_.empty();
  const bool exit_rule = opt_.pocket_exit && !pocket_.empty();
  const uint32_t pocket_cost = pockets ? static_cast<uint32_t>(std::lround(pocket_moves_ * dist_.guidance().min_forward())) : 0;
  for (size_t op = 0; op < m; ++op) {
    const bool wait = static_cast<int>(op) == wait_;
    int o = 0;
    if (!walk(i, static_cast<int>(op), cells, edges, &o)) continue;
    uint32_t cost = 0;
    int first = 0;  // the action after which it first stands on its goal (0: never)
    const bool own = tf_ && tf_->has(i);  // traffic flow: its own guide table gives h
    if (!guided_ && !own) {
      if (!on_goal)
        for (int d = 0; d < D && !first; ++d)
          if (cells[d] == goal) first = d + 1;
      if (first) cost = static_cast<uint32_t>(first);
      else cost = static_cast<uint32_t>(D) + dist_.get(goal_table_[i], cells[D - 1], o);
    } else {
      // The same with each action at its guided cost (1 each without guidance); with its
      // own table, in that table's kScale units plus its congestion-aware h of the end state.
      const uint32_t unit = own ? TrafficFlow::kScale : 1;
      const std::string& a = ops_[op].acts;
      Vertex v = current_[i];
      int hd = heading_[i];
      for (int d = 0; d < D; ++d) {
        if (a[d] == 'F') cost += unit * dist_.forward_cost(v, hd), v = cells[d];
        else if (a[d] == 'W') cost += unit * wait_cost_;
        else cost += unit * dist_.turn_cost(), hd = heading_after(hd, a[d]);
        if (!on_goal && cells[d] == goal) {
          first = d + 1;
          break;
        }
      }
      if (!first) cost += own ? std::min<uint32_t>(tf_->h(i, cells[D - 1], o), 1u << 24) : dist_.get(goal_table_[i], cells[D - 1], o);
    }
    if (pockets) {
      const Vertex mine = pocket_[goal];
      Vertex from = current_[i];
      for (int d = 0; d < D; ++d) {
        const Vertex p = pocket_[cells[d]];
        if (p >= 0 && p != pocket_[from] && p != mine) {  // enters a foreign pocket
          cost += (own ? TrafficFlow::kScale : 1) * pocket_cost;
          break;
        }
        from = cells[d];
      }
    }
    if (tf_ && !own) cost *= TrafficFlow::kScale;  // one scale for every robot (LNS gains)
    // The exit rule: never deeper into a pocket that a robot has to leave (not a candidate;
    // its gain for LNS stays defined).
    const bool blocked = exit_rule && enters_blocked_pocket(i, cells);
    score_of_[static_cast<size_t>(i) * m + op] = cost * static_cast<uint32_t>(m) + static_cast<uint32_t>(op);
    if ((wait && !opt_.wait_op && !on_goal) || blocked) continue;
    c[k++] = {cost, static_cast<uint8_t>(op)};
  }
  std::stable_sort(c, c + k);  // cost, then the better operation
  uint8_t* out = &cand_[static_cast<size_t>(i) * m];
  for (int j = 0; j < k; ++j) out[j] = c[j].second;
  ncand_[i] = static_cast<uint8_t>(k);
}

Epibt::Result Epibt::build(int i, double root_key, bool lns)
{
  if ((++calls_ & 15) == 0 && deadline_ != Clock::time_point::max() && Clock::now() >= deadline_) timed_out_ = true;
  if (timed_out_) return Rejected;
  if (visited_[i] != round_) visits_[i] = 0, visited_[i] = round_;
  ++visits_[i];
  placed_[i] = round_;  // on the current chain: nobody may take its place now
  candidates(i);
  const int old = op_[i];
  const uint8_t* cand = &cand_[static_cast<size_t>(i) * ops_.size()];
  for (int k = 0; k < ncand_[i]; ++k) {
    set_op(i, cand[k]);
    const int j = conflict(i);
    if (j == -1) {
      place(i);
      if (lns && score_ < lns_floor_) {  // LNS: worse than before this root's attempt
        unplace(i);
        set_op(i, old);
        return Rejected;
      }
      return Accepted;
    }
    if (j == -2) continue;
    if (placed_[j] == round_ || (visited_[j] == round_ && visits_[j] >= (lns ? opt_.lns_revisit : opt_.revisit)) || (!lns && key_[j] >= root_key)) continue;
    unplace(j);
    place(i);
    const Result r = build(j, root_key, lns);
    if (r == Accepted) return Accepted;
    unplace(i);
    place(j);  // j's operation was restored by its failed build
    if (r == Rejected) {
      set_op(i, old);
      return Rejected;
    }
  }
  set_op(i, old);
  placed_[i] = 0;
  return Failed;
}

void Epibt::lns()
{
  const int n = static_cast<int>(current_.size());
  for (int k = 0; k < n; ++k) {  // the paper's weights: rank in priority order, squared
    const double w = static_cast<double>(n + 1 - k) / (n + 1);
    power_[order_[k]] = w * w;
    candidates(order_[k]);
  }
  scoring_ = true;
  score_ = 0;
  for (int i = 0; i < n; ++i) score_ += gain(i);
  std::vector<int32_t> order = order_;
  for (int round = 0; (opt_.lns_rounds < 0 || round < opt_.lns_rounds) && !timed_out_; ++round) {
    rng_.shuffle(order.data(), n);
    ++round_;
    const double before = score_;
    for (int32_t i : order) {
      if (timed_out_) break;
      if (visited_[i] == round_) continue;
      lns_floor_ = score_ - 1e-9;
      unplace(i);
      if (build(i, 0.0, true) != Accepted) place(i);
    }
    ++lns_rounds_done_;
    if (opt_.lns_converge && score_ <= before + 1e-9) break;  // a round that gained nothing: converged
  }
  scoring_ = false;
}

Status Epibt::search(const Budget& b)
{
  if (planned_) return at_goal() ? Status::Solved : Status::Searching;
  const int n = static_cast<int>(current_.size());
  const Clock::time_point start = Clock::now();
  deadline_ = b.deadline_from(start);
  timed_out_ = false;
  if (tf_) tf_work(deadline_ == Clock::time_point::max() ? deadline_ : start + std::chrono::duration_cast<Clock::duration>((deadline_ - start) * opt_.tf.share));
  ++stamp_;
  ++round_;
  if (opt_.pocket_exit) exit_.mark(current_, goals_);  // pockets that a robot in them has to leave
  for (int i = 0; i < n; ++i)
    key_[i] = opt_.priority == Priority::Age ? age_[i] : -static_cast<double>(h(i));
  if (opt_.pocket_exit && opt_.leavers_first && exit_.any())
    for (int i = 0; i < n; ++i)
      if (exit_.leaving(current_[i], goals_[i])) key_[i] += kLeaverKey;
  for (int i = 0; i < n; ++i) order_[i] = i;
  std::stable_sort(order_.begin(), order_.end(), [this](int32_t x, int32_t y) { return key_[x] > key_[y]; });
  for (int32_t i : order_) {
    if (timed_out_) break;
    if (visited_[i] == round_) continue;  // replanned (or tried) through someone else: final
    unplace(i);
    if (build(i, key_[i], false) != Accepted) place(i);  // keeps its operation
  }
  if (opt_.lns_rounds != 0 && !timed_out_) lns();
  if (timed_out_) ++timeouts_;
  const size_t D = static_cast<size_t>(opt_.depth);
  for (int i = 0; i < n; ++i) {
    action_[i] = ops_[static_cast<size_t>(op_[i])].acts[0];
    next_[i] = cells_[static_cast<size_t>(i) * D];
  }
  planned_ = true;
  ++steps_planned_;
  return at_goal() ? Status::Solved : Status::Searching;
}

const Config& Epibt::next()
{
  if (!planned_) search(Budget{});
  return next_;
}

void Epibt::commit()
{
  if (!planned_) search(Budget{});
  const int n = static_cast<int>(current_.size());
  for (int i = 0; i < n; ++i) unplace(i);
  for (int i = 0; i < n; ++i) {
    if (tf_ && action_[i] == 'F') tf_->advance(i, current_[i], heading_[i]);
    current_[i] = next_[i];
    heading_[i] = heading_after(heading_[i], action_[i]);
    // The tail of the operation (still jointly conflict-free), or wait (no inheritance).
    set_op(i, opt_.inherit ? ops_[static_cast<size_t>(op_[i])].next : wait_);
    // Priority::Age: PIBT's dynamic priority (+1 per step off the goal; a dead end first).
    age_[i] = current_[i] != goals_[i] ? age_[i] + 1.0 : age_[i] - static_cast<double>(static_cast<long>(age_[i]));
    if (current_[i] != goals_[i] && g_.degree(current_[i]) == 1) age_[i] += 10.0;
  }
  for (int i = 0; i < n; ++i) place(i);
  planned_ = false;
}

}  // namespace planner
