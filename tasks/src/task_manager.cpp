#include "tasks/task_manager.hpp"

#include "tasks/escalation.hpp"

#include <algorithm>
#include <stdexcept>

namespace tasks {

void TaskManager::start(const planner::Config& positions)
{
  holding_.assign(positions.size(), -1);
  goals_ = positions;
  now_ = 0;
  if (free_flow_) free_flow_->start(positions);
  if (battery_) battery_->step(positions);  // the start charges
  on_start(positions);
  refresh_goals(positions);
  observe_stalls(positions);
}

void TaskManager::watch_stalls(const planner::Graph& g)
{
  stalls_ = std::make_unique<ErrandStalls>(g);
  stalls_->set_sticky(urgency_.sticky);
  pocket_.assign(g.size(), -1);
  dead_end_pocket_.assign(g.size(), -1);
  for (const std::vector<planner::Vertex>& t : file_->tasks)
    for (planner::Vertex v : t) {
      if (pocket_[v] >= 0) continue;
      pocket_[v] = v;
      for (planner::Vertex u : dead_end_corridor(g, v)) {
        if (pocket_[u] < 0) pocket_[u] = v;
        if (dead_end_pocket_[u] < 0) dead_end_pocket_[u] = v;
      }
    }
}

void TaskManager::observe_stalls(const planner::Config& positions)
{
  if (!stalls_) return;
  std::vector<ErrandStalls::Held> held(positions.size());
  for (int a = 0; a < num_agents(); ++a)
    if (const Task* k = task_of(a)) held[a] = {k->id, k->next, k->next_cell()};
  stalls_->observe(now_, held, positions);
  observe_escalation();
}

bool TaskManager::escalated(int agent) const
{
  const Task* k = task_of(agent);
  if (!k) return false;
  const auto it = escalation_.find(k->id);
  return it != escalation_.end() && it->second.on && it->second.errand == k->next;
}

void TaskManager::observe_escalation()
{
  const int after = urgency_.escalate_after;
  if (after <= 0) return;
  for (int a = 0; a < num_agents(); ++a) {
    const Task* k = task_of(a);
    if (!k) continue;
    const long mark = stalls_->last_mark(k->id);
    Escalation& e = escalation_[k->id];
    if (e.errand != k->next) e = {k->next, mark, 0, false, now_};  // a new errand (or task)
    e.seen = now_;
    if (e.on) continue;
    if (mark != e.mark) e.mark = mark, e.heading_stall = 0;  // progress
    if (mark < now_ && heading(a)) ++e.heading_stall;
    e.on = e.heading_stall >= after;
  }
  // Tasks nobody holds any more (done, or handed back to the pool: a new holder starts anew).
  for (auto it = escalation_.begin(); it != escalation_.end();)
    it = it->second.seen == now_ ? std::next(it) : escalation_.erase(it);
}

std::vector<Event> TaskManager::update(long t, const planner::Config& positions)
{
  std::vector<Event> events;
  now_ = t;
  const std::vector<int> charged = battery_ ? battery_->step(positions) : std::vector<int>{};
  for (int a = 0; a < num_agents(); ++a) {
    const int s = holding_[a];
    if (s < 0) continue;
    Task& k = slots_[s];
    if (positions[a] != k.next_cell()) continue;
    events.push_back({t, a, k.id, k.next});
    if (stalls_) stalls_->completed(t, k.id, k.next);
    if (free_flow_) free_flow_->errand(a, k.next_cell());
    ++k.next;
    ++errands_finished_;
    if (k.finished()) {
      ++tasks_finished_;
      const Task done = k;
      holding_[a] = -1;
      assignments_.push_back({t, a, -1});
      drop(s);
      // Low: to a charger before the next task (a round-robin agent gets it there).
      if (battery_) battery_->consider(a, positions[a]);
      on_finished(a, done);
    }
  }
  const bool handed = hand_back(positions);
  if (battery_) send_to_charge(positions);
  for (int a : charged) on_charged(a);
  goals_changed_ = false;
  const bool rematch = handed || rematch_;
  rematch_ = false;
  if (!events.empty() || queues_ || parking_ || battery_ || rematch) {
    const planner::Config before = goals_;
    if (!events.empty() || !charged.empty() || rematch) after_step(positions);
    refresh_goals(positions);
    goals_changed_ = !events.empty() || handed || goals_ != before;
    // An agent that just reached a queue or parking goal: the epoch waited for it.
    at_goal_.resize(num_agents(), 0);
    for (int a = 0; a < num_agents(); ++a) {
      const bool at = positions[a] == goals_[a];
      if (at && !at_goal_[a] && awaited(a) && !heading(a)) goals_changed_ = true;
      at_goal_[a] = at;
    }
  }
  exchange_tasks(positions);
  observe_stalls(positions);
  return events;
}

int64_t TaskManager::task_moves(planner::Vertex from, const Task& t)
{
  if (!task_dist_) return 0;
  int64_t moves = 0;
  planner::Vertex at = from;
  for (size_t k = static_cast<size_t>(t.next); k < t.errands.size(); ++k) {
    const int32_t d = task_dist_->from_goal(t.errands[k], at);
    if (d == planner::DistCache::kInf) return 0;
    moves += d;
    at = t.errands[k];
  }
  return moves;
}

void TaskManager::swap_tasks(int a, int b)
{
  std::swap(holding_[a], holding_[b]);
  slots_[holding_[a]].agent = a;
  slots_[holding_[b]].agent = b;
  assignments_.push_back({now_, a, slots_[holding_[a]].id});
  assignments_.push_back({now_, b, slots_[holding_[b]].id});
}

const Task* TaskManager::task_of(int agent) const
{
  return holding_[agent] >= 0 ? &slots_[holding_[agent]] : nullptr;
}

planner::Config TaskManager::open_errands() const
{
  planner::Config open(num_agents(), -1);
  for (int a = 0; a < num_agents(); ++a)
    if (const Task* k = task_of(a)) open[a] = k->next_cell();
  return open;
}

std::vector<TaskManager::Upcoming> TaskManager::upcoming() const
{
  std::vector<Upcoming> out;
  for (int a = 0; a < num_agents(); ++a)
    if (const Task* k = task_of(a); k && k->next + 1 < static_cast<int>(k->errands.size()))
      out.push_back({a, k->errands[k->next + 1]});
  return out;
}

Task TaskManager::make_task(long id) const
{
  Task t;
  t.id = id;
  t.line = static_cast<int>(id % file_->size());
  t.errands = file_->tasks[t.line];
  return t;
}

int TaskManager::add_task(Task t)
{
  t.agent = -1;
  revealed_.push_back({t.id, t.line, now_});
  if (!free_slots_.empty()) {
    const int s = free_slots_.back();
    free_slots_.pop_back();
    slots_[s] = std::move(t);
    return s;
  }
  slots_.push_back(std::move(t));
  return static_cast<int>(slots_.size()) - 1;
}

void TaskManager::give(int agent, int s)
{
  slots_[s].agent = agent;
  holding_[agent] = s;
  ++tasks_assigned_;
  assignments_.push_back({now_, agent, slots_[s].id});
}

void TaskManager::release(int agent)
{
  const int s = holding_[agent];
  if (s < 0) return;
  slots_[s].agent = -1;
  holding_[agent] = -1;
  assignments_.push_back({now_, agent, -1});
  --tasks_assigned_;  // counts tasks handed out for good, not matching rounds
}

void TaskManager::drop_task(int agent)
{
  const int s = holding_[agent];
  if (s < 0) return;
  release(agent);
  on_dropped(agent, s);
}

bool TaskManager::hand_back(const planner::Config& positions)
{
  bool any = false;
  for (int a = 0; a < num_agents(); ++a) {
    if (holding_[a] < 0) continue;
    if (battery_ && battery_->critical(a)) {
      // Charge first: the task would take it to empty (battery.hpp).
      drop_task(a);
      ++dropped_for_charge_;
      battery_->consider(a, positions[a]);  // no charger free: send_to_charge() retries
      any = true;
    } else if (reach_ && reassigns_for_closures() && !reach_->reaches(positions[a], slots_[holding_[a]].next_cell())) {
      drop_task(a);
      ++reassigned_for_closure_;
      any = true;
    }
  }
  return any;
}

void TaskManager::set_open_graph(const planner::Graph* open)
{
  reach_ = open ? std::make_unique<Reachability>(*open) : nullptr;
  rematch_ = true;
}

void TaskManager::drop(int s)
{
  slots_[s] = Task{};
  free_slots_.push_back(s);
}

std::vector<int> TaskManager::live_slots() const
{
  std::vector<int> out;
  for (int s = 0; s < static_cast<int>(slots_.size()); ++s)
    if (slots_[s].id >= 0) out.push_back(s);
  std::sort(out.begin(), out.end(), [&](int a, int b) { return slots_[a].id < slots_[b].id; });
  return out;
}

void TaskManager::set_queues(const planner::Graph& g, const QueueOptions& options)
{
  queues_.reset();
  if (!options.on()) return;
  queues_ = std::make_unique<StationQueues>(g, file_->errand_cells(), options);
  if (!parking_) parking_ = std::make_unique<Parking>(g, std::vector<planner::Vertex>{});
}

void TaskManager::set_parking(const planner::Graph& g, std::vector<planner::Vertex> cells)
{
  parking_ = std::make_unique<Parking>(g, std::move(cells));
}

void TaskManager::set_battery(const planner::Graph& g, BatteryOptions options, std::vector<Charger> chargers,
                              std::vector<std::pair<double, double>> xy)
{
  battery_ = std::make_unique<Battery>(g, options, std::move(chargers), std::move(xy));
  task_dist_ = std::make_unique<planner::DistTable>(g, 256);  // a table per errand cell, LRU-capped
  reserved_.assign(g.size(), 0);
  // Agents waiting for a charger idle for long: off the errand stations and their dead ends,
  // where the traffic to the stations would push them about (and drain them) the whole time.
  station_cells_.assign(g.size(), 0);
  for (const std::vector<planner::Vertex>& t : file_->tasks)
    for (planner::Vertex v : t) {
      if (station_cells_[v]) continue;
      station_cells_[v] = 1;
      for (planner::Vertex u : dead_end_corridor(g, v)) station_cells_[u] = 1;
    }
  if (!parking_) parking_ = std::make_unique<Parking>(g, std::vector<planner::Vertex>{});
}

void TaskManager::set_grid_battery(const planner::Graph& g, BatteryOptions options,
                                   const std::vector<planner::Vertex>& chargers, double charge_w)
{
  if (const std::string why = battery_problem(options); !why.empty()) throw std::invalid_argument(why);
  if (!g.is_grid()) throw std::invalid_argument("chargers: a battery needs a grid map (cell centres)");
  if (options.charging && chargers.empty()) throw std::invalid_argument("chargers: charging is on, but no charger cell is given");
  if (options.charging && !(charge_w > 0)) throw std::invalid_argument("charge_w: must be > 0 with charging on");
  std::vector<Charger> cs;
  for (planner::Vertex v : chargers) {
    if (v < 0 || v >= g.size()) throw std::invalid_argument("chargers: cell " + std::to_string(v) + " is not on the map");
    for (const Charger& c : cs)
      if (c.cell == v) throw std::invalid_argument("chargers: cell " + std::to_string(v) + " is given twice: one agent charges on a cell");
    cs.push_back({v, charge_w / 3600.0, "charger" + std::to_string(cs.size())});
  }
  std::vector<std::pair<double, double>> xy;
  for (planner::Vertex v = 0; v < g.size(); ++v) xy.emplace_back(g.cell_x(v), g.cell_y(v));
  set_battery(g, options, std::move(cs), std::move(xy));
}

bool TaskManager::send_to_charge(const planner::Config& positions)
{
  // The lowest charge first: when chargers are short, the agent nearest to empty gets one.
  std::vector<int> order;
  for (int a = 0; a < num_agents(); ++a)
    if (holding_[a] < 0 && !battery_->charging(a) && battery_->wants(a)) order.push_back(a);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return battery_->charge(a) < battery_->charge(b); });
  bool any = false;
  for (int a : order) any = battery_->consider(a, positions[a]) || any;
  return any;
}

void TaskManager::refresh_goals(const planner::Config& positions)
{
  for (int a = 0; a < num_agents(); ++a)
    goals_[a] = holding_[a] >= 0 ? slots_[holding_[a]].next_cell() : charging(a) ? battery_->goal(a) : positions[a];
  std::vector<char> unplaced(num_agents(), 0);
  if (queues_) {
    std::vector<planner::Vertex> errand(num_agents(), -1);
    for (int a = 0; a < num_agents(); ++a)
      if (holding_[a] >= 0) errand[a] = slots_[holding_[a]].next_cell();
    queues_->apply(errand, positions, goals_, unplaced);
  }
  if (parking_) {
    // Idle agents, and busy ones beyond their station's queue, wait parked.
    std::vector<char> idle(num_agents());
    for (int a = 0; a < num_agents(); ++a) idle[a] = (holding_[a] < 0 && !charging(a)) || unplaced[a];
    const bool clear = queues_ && queues_->options().idle_clear;
    // idle_clear: the cells beside a dead-end station's mouth are no rest cells either.
    const std::vector<uint8_t>* reserved = !queues_ ? nullptr : clear ? &queues_->clear_cells() : &queues_->reserved_cells();
    if (battery_) {  // an idle agent must not stand on a charger or a station (or in their dead ends) either
      for (size_t v = 0; v < reserved_.size(); ++v) reserved_[v] = battery_->reserved(v) || station_cells_[v] || (reserved && (*reserved)[v]);
      reserved = &reserved_;
    }
    parking_->apply(idle, positions, reserved, goals_, queues_ ? &queues_->in_use_cells() : nullptr);
  }
  evict(positions);
}

void TaskManager::evict(const planner::Config& positions)
{
  // Escalation (escalation.hpp): an idle agent standing in the dead-end pocket of an escalated
  // errand's cell goes to the nearest cell outside the pockets, and keeps that goal until it
  // stands there or gets a task (else it would stop at the pocket's mouth).
  if (urgency_.escalate_after <= 0 || !stalls_) return;
  evict_.resize(num_agents(), -1);
  const std::vector<char> clear = escalated_pockets(*this, escalated_agents(*this));
  for (int a = 0; a < num_agents(); ++a) {
    const bool idle = holding_[a] < 0 && !charging(a) && goals_[a] == positions[a];
    if (!idle || evict_[a] == positions[a]) evict_[a] = -1;
    if (idle && evict_[a] < 0 && !clear.empty() && clear[positions[a]])
      evict_[a] = evict_cell(stalls_->graph(), dead_end_pocket_, positions[a], queues_ ? &queues_->reserved_cells() : nullptr);
    if (idle && evict_[a] >= 0) goals_[a] = evict_[a];
  }
}

}  // namespace tasks
