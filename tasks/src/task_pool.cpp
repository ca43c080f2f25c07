#include "tasks/task_pool.hpp"

#include <algorithm>

namespace tasks {

TaskPool::TaskPool(std::shared_ptr<const TaskFile> file, const planner::Graph& g, int pool_size,
                   std::unique_ptr<TaskAssigner> assigner, bool reassign)
    : TaskManager(std::move(file)), dist_(g), pool_size_(pool_size), assigner_(std::move(assigner)), reassign_(reassign)
{
  chain_by_line_.assign(file_->size(), -1);
  // Keep the tables of the tasks being matched plus a cache; drop the rest (chain lengths
  // are computed once per file line and would otherwise keep a table per errand cell).
  dist_.set_max_tables(static_cast<size_t>(pool_size_) + 256);
}

int TaskPool::chain_length(const Task& t)
{
  int& c = chain_by_line_[t.line];
  if (c < 0) {
    c = 0;
    // Distances are symmetric (undirected graph): look each leg up in the table of its *start*.
    // Tasks start at a few pick-up stations (352 cells on LoRR's WAREHOUSE) but end anywhere
    // (24,768 cells), so tables per start errand are far fewer than tables per end errand.
    for (size_t k = 1; k < t.errands.size(); ++k) c += dist_.from_goal(t.errands[k - 1], t.errands[k]);
  }
  return c;
}

int64_t TaskPool::cost(planner::Vertex pos, const Task& t)
{
  return static_cast<int64_t>(dist_.from_goal(t.errands[t.next], pos)) + chain_length(t);
}

void TaskPool::on_start(const planner::Config& positions)
{
  for (int k = 0; k < pool_size_; ++k) add_task(make_task(next_id_++));
  assign_free(positions);
}

void TaskPool::on_finished(int, const Task&)
{
  // Tasks revealed past pool_size during a closure (top_up) are used up first.
  if (static_cast<int>(live_slots().size()) < pool_size_) add_task(make_task(next_id_++));
}

void TaskPool::top_up(const planner::Config& positions)
{
  if (!closures()) return;
  std::vector<int> live = live_slots();
  auto reachable = [&](const Task& t) {
    for (planner::Vertex p : positions)
      if (can_reach(p, t.next_cell())) return true;
    return false;
  };
  int usable = 0;
  for (int s : live) usable += reachable(slot(s));
  for (int n = static_cast<int>(live.size()); usable < pool_size_ && n < 2 * pool_size_; ++n)
    usable += reachable(slot(add_task(make_task(next_id_++))));
}

std::vector<int64_t> TaskPool::load_costs(const std::vector<int>& cols)
{
  std::vector<int64_t> out(cols.size(), 0);
  const int w = urgency().load_cost;
  if (w <= 0) return out;
  load_.resize(static_cast<size_t>(dist_.cache()->graph().size()), 0);
  std::vector<planner::Vertex> touched;
  for (int s : live_slots()) {
    const Task& t = slot(s);
    if (t.agent < 0) continue;
    for (size_t e = static_cast<size_t>(t.next); e < t.errands.size(); ++e) {
      if (load_[t.errands[e]]++ == 0) touched.push_back(t.errands[e]);
    }
  }
  for (size_t j = 0; j < cols.size(); ++j) {
    const Task& t = slot(cols[j]);
    for (size_t e = static_cast<size_t>(t.next); e < t.errands.size(); ++e) out[j] += static_cast<int64_t>(w) * load_[t.errands[e]];
  }
  for (planner::Vertex v : touched) load_[v] = 0;
  return out;
}

void TaskPool::hand_over_stalled(const planner::Config& positions)
{
  const int T = urgency().swap_after;
  const ErrandStalls* st = stalls();
  if (T <= 0 || !st) return;
  // Agents heading for the cell of a task's first errand, with its stall.
  struct Cand {
    int agent;
    long long stall;
  };
  std::vector<Cand> c;
  for (int a = 0; a < num_agents(); ++a)
    if (heading(a) && !task_of(a)->opened()) c.push_back({a, st->stalled(now(), task_of(a)->id)});
  std::vector<Cand> over;
  for (const Cand& k : c)
    if (k.stall >= T) over.push_back(k);
  if (over.empty()) return;
  std::sort(over.begin(), over.end(), [](const Cand& x, const Cand& y) { return x.stall != y.stall ? x.stall > y.stall : x.agent < y.agent; });
  std::vector<char> swapped(num_agents(), 0);
  const planner::Graph &sg = st->graph(), &pg = dist_.graph();  // the same distances: the pool's (as before)
  const bool same = &sg == &pg || (sg.size() == pg.size() && sg.move_costs() == pg.move_costs());
  for (const Cand& k : over) {
    const int a = k.agent;
    if (swapped[a]) continue;
    const planner::Vertex cell = task_of(a)->next_cell();
    // Only nearer than the errand has been: a handover never lets the stall metric's new
    // holder (errand_stalls.hpp) start farther away than the errand already was. In the
    // metric's distances when its graph is not the pool's (routing costs on the pool's).
    auto dist = [&](planner::Vertex v) { return same ? dist_.from_goal(cell, v) : st->distance(cell, v); };
    int32_t best = dist(positions[a]);
    if (const int32_t b = st->best(task_of(a)->id); b >= 0) best = std::min(best, b);
    int pick = -1;
    for (const Cand& o : c) {
      const int b = o.agent;
      if (b == a || swapped[b] || o.stall >= k.stall || task_of(b)->next_cell() != cell) continue;
      const int32_t d = dist(positions[b]);
      if (d < best) best = d, pick = b;
    }
    if (pick < 0) continue;
    swap_tasks(a, pick);
    swapped[a] = swapped[pick] = 1;
    ++handovers_;
  }
}

void TaskPool::after_step(const planner::Config& positions)
{
  top_up(positions);
  if (reassign_) steal_rounds(positions);
  else assign_free(positions);
}

std::vector<int> TaskPool::admissible(const std::vector<int>& cols) const
{
  const StationQueues* q = queues();
  if (!q || q->options().admission < 0) return cols;
  std::vector<int> held(q->num_stations(), 0), marks;
  // The stations of a task's remaining errands, each once.
  auto stations = [&](const Task& t) {
    marks.clear();
    for (size_t e = t.next; e < t.errands.size(); ++e)
      if (const int i = q->station_index(t.errands[e]); i >= 0 && std::find(marks.begin(), marks.end(), i) == marks.end())
        marks.push_back(i);
    return marks;
  };
  for (int s : live_slots())
    if (slot(s).agent >= 0)
      for (int i : stations(slot(s))) ++held[i];
  std::vector<int> out;
  for (int s : cols) {
    if (slot(s).agent >= 0) {
      out.push_back(s);
      continue;
    }
    bool room = true;
    for (int i : stations(slot(s))) room = room && held[i] < q->admission_limit(i);
    if (!room) continue;
    for (int i : marks) ++held[i];
    out.push_back(s);
  }
  return out;
}

void TaskPool::steal_rounds(const planner::Config& positions)
{
  std::vector<int> agents;
  for (int a = 0; a < num_agents(); ++a)
    if (assignable(a)) agents.push_back(a);
  // Each steal strictly shortens the stolen task's first leg, so this ends; the round
  // limit only bounds the work of one step.
  for (int round = 0; round < 8 && !agents.empty(); ++round) {
    std::vector<int> cols;  // unopened tasks, and opened ones handed back
    for (int s : live_slots())
      if (slot(s).next == 0 || slot(s).agent < 0) cols.push_back(s);
    cols = admissible(cols);
    if (cols.empty()) return;
    planner::Config in_use;
    for (int s : cols) in_use.push_back(slot(s).next_cell());
    dist_.set_goals(in_use);
    std::vector<int64_t> held(cols.size(), kForbidden);  // holder's distance to the first errand
    for (size_t j = 0; j < cols.size(); ++j)
      if (const int b = slot(cols[j]).agent; b >= 0) held[j] = dist_.from_goal(slot(cols[j]).errands[0], positions[b]);
    std::vector<char> poor(agents.size(), 0);  // some task was beyond its charge
    const std::vector<int64_t> extra = load_costs(cols);
    auto c = [&](int i, int j) -> int64_t {
      const Task& t = slot(cols[j]);
      if (!can_reach(positions[agents[i]], t.next_cell())) return kForbidden;
      const int64_t d = dist_.from_goal(t.next_cell(), positions[agents[i]]);
      if (t.agent >= 0 && d >= held[j]) return kForbidden;  // only a strictly nearer agent may take it
      if (!affords(agents[i], d + chain_length(t), t)) {
        poor[i] = 1;
        return kForbidden;
      }
      return d + chain_length(t) + extra[j];
    };
    const std::vector<int> match = assigner_->assign(static_cast<int>(agents.size()), static_cast<int>(cols.size()), c);
    std::vector<int> displaced;
    for (size_t i = 0; i < agents.size(); ++i) {
      if (match[i] < 0 || c(static_cast<int>(i), match[i]) >= kForbidden) {
        if (poor[i]) charge_instead(agents[i], positions[agents[i]]);
        continue;
      }
      const int s = cols[match[i]];
      if (const int b = slot(s).agent; b >= 0) {
        release(b);
        displaced.push_back(b);
        ++reassignments_;
      }
      give(agents[i], s);
    }
    agents = std::move(displaced);
  }
}

void TaskPool::assign_free(const planner::Config& positions)
{
  std::vector<int> agents, cols;
  for (int a = 0; a < num_agents(); ++a)
    if (assignable(a)) agents.push_back(a);
  if (agents.empty()) return;
  for (int s : live_slots())
    if (slot(s).agent < 0) cols.push_back(s);
  cols = admissible(cols);
  if (cols.empty()) return;
  planner::Config in_use;
  for (int s : cols) in_use.push_back(slot(s).errands[slot(s).next]);
  dist_.set_goals(in_use);  // marks their tables in use; evicts idle ones over the cap
  std::vector<char> poor(agents.size(), 0);  // some task was beyond its charge
  const std::vector<int64_t> extra = load_costs(cols);
  auto c = [&](int i, int j) -> int64_t {
    const Task& t = slot(cols[j]);
    if (!can_reach(positions[agents[i]], t.next_cell())) return kForbidden;
    const int64_t moves = cost(positions[agents[i]], t);
    if (!affords(agents[i], moves, t)) {
      poor[i] = 1;
      return kForbidden;
    }
    return moves + extra[j];
  };
  const std::vector<int> match = assigner_->assign(static_cast<int>(agents.size()), static_cast<int>(cols.size()), c);
  for (size_t i = 0; i < agents.size(); ++i) {
    if (match[i] >= 0 && c(static_cast<int>(i), match[i]) < kForbidden) give(agents[i], cols[match[i]]);
    else if (poor[i]) charge_instead(agents[i], positions[agents[i]]);  // no work it can finish: charge first
  }
}

}  // namespace tasks
