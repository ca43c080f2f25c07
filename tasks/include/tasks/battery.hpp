#pragma once
// Battery: each agent's charge, drained by driving, and the charging errands that keep it
// above empty (issue 24, "charging"; Open-RMF's battery model, openTCS's charging orders).
//
// Drain: `per_m_wh` for every metre between the centres of consecutive cells and
// `per_turn_wh` for every change of direction (a reversal counts as one turn); standing
// costs nothing. The drain is counted on the positions the task layer sees at each step's
// end, so it is the same for every executor and for the grid runner.
//
// Charging errand: an agent below `threshold` (fraction of capacity) that holds no task
// claims the nearest unclaimed charger (breadth-first along arcs), heads there and stands
// on it, gaining the charger's rate per step, until it reaches `target`; then it releases
// the charger and is free for work again. The low charge is acted on between tasks, so
// `threshold` should cover the longest task plus the way to a charger. A task longer than
// that (or a start below it) is caught by `critical`: an agent that drops below it in the
// middle of a task hands the task back (TaskManager: the pool gives it to another agent; a
// round-robin agent resumes it after charging) and goes to charge at once, so it never runs
// empty on its way (critical must cover the way from anywhere to the nearest charger; 0:
// off). With no charger free, the agent waits idle (taking no task) and retries at every
// step.
//
// Reserve (distance-aware; `reserve_margin` > 0, default 1.5): a fixed `critical` fraction
// covers the way to a charger only where chargers are near, and a detour or a head-on
// standoff on the way drains more than the shortest path. So an agent also counts as low
// (between tasks) and as critical (mid-task: the task goes back) when its charge is below
// reserve_margin x the energy of the shortest way from its cell to the nearest charger it
// could claim (free or its own; all taken: the nearest): per_m_wh x metres + per_turn_wh x
// (turns along that way + 1, its first move may turn). The ways are one reverse Dijkstra
// per charger on metres, at construction. 0: off (critical alone).
//
// A task only if it can be done (`task_check`, default; reserve_margin > 0, charging on):
// before a pool agent is given a task, its charge must cover reserve_margin x (the task's
// moves -- to its first errand and along its errands -- at the most one move can drain,
// `move_wh()`: the longest arc's metres plus a turn, and the way from its last errand to the
// nearest charger). Otherwise it goes to charge first (`charge_first`). An agent charged to
// `target` affords any task (charging cannot give it more; the mid-task reserve catches it).
// The mid-task reserve alone came too late: an agent that took a long task near the
// reserve's edge dropped it far from the chargers, and when the nearest one was taken the
// next free one was out of its reach (bench_charging.py --per-m-wh 1.5 --critical 0.25,
// seed 1: one AGV ran empty). A round-robin agent's next task is fixed: one it cannot afford
// waits until the agent has charged (roundrobin.hpp).
//
// Claims rematched (`rematch`, default on): two agents on their way to chargers swap their
// claims when the swap makes the sum of their ways (metres) strictly shorter, checked at
// every step() for every pair not yet standing on its charger. Without it, two agents head-on
// in a one-lane aisle, each with its charger behind the other, can oscillate there until
// empty (the planner restarts its search at every new goal elsewhere in the fleet; seen in
// SUMO at 1.5 Wh/m). With the swap each heads for the charger on its own side. Every swap
// shortens the sum strictly, so claims cannot swap back at the same cells. A swap is made
// only if each agent's charge covers the way to its new charger. An agent whose charge
// reaches 0 counts as run empty (once); the model does not stop it, the metric says the
// fleet was mis-sized (it must stay 0).
//
// TaskManager owns one (TaskManager::set_battery) and excludes charging agents from
// assignment (tasks/task_manager.hpp).
#include <string>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace tasks {

// The corridor (cells of at most two neighbours, either way) that joins `v` to the rest of
// `g` through exactly one junction, `v` included; empty when `v` is not at such a dead end.
std::vector<planner::Vertex> dead_end_corridor(const planner::Graph& g, planner::Vertex v);

struct BatteryOptions {
  double capacity_wh = 100;
  double initial = 1.0;      // fraction of capacity at the start, every agent
  double per_m_wh = 0;       // drain per metre driven
  double per_turn_wh = 0;    // drain per change of direction
  double threshold = 0.3;    // below this fraction an agent between tasks goes to charge
  double critical = 0.1;     // below this one (< threshold) an agent drops its task to charge; 0: off
  double target = 0.9;       // it leaves the charger at this fraction
  double reserve_margin = 1.5;  // low / critical also below this x the energy to the nearest charger; 0: off
  bool rematch = true;          // agents on their way swap claims when that shortens both ways' sum
  bool task_check = true;       // a task only if the charge covers it and the way on to a charger (with the margin)
  bool charging = true;      // false: drain only (no charging errands)
};

// The first bad field of `o` as "key: what is wrong" ("" when fine), with the YAML key
// names (fleet.battery.*): the apps prefix their option names.
std::string battery_problem(const BatteryOptions& o);

struct Charger {
  planner::Vertex cell = -1;
  double wh_per_step = 0;  // energy one step on it adds (power x efficiency x step time)
  std::string id;
};

class Battery {
 public:
  // `xy`: per vertex, the cell centre in metres (distances and turns; std::invalid_argument
  // if it has another size, or a charger is no vertex); `chargers` may be
  // empty only with options.charging false.
  Battery(const planner::Graph& g, BatteryOptions options, std::vector<Charger> chargers,
          std::vector<std::pair<double, double>> xy);

  // The end of one step: agents now stand on `positions`. Drains the moves since the last
  // call, charges agents standing on their claimed charger, releases those at target.
  // Returns the agents that finished charging in this step.
  std::vector<int> step(const planner::Config& positions);

  // Agent a holds no task: send it to charge if it is low. Returns true while it charges.
  bool consider(int a, planner::Vertex at);
  bool charging(int a) const { return a < static_cast<int>(claim_.size()) && claim_[a] >= 0; }
  // The claimed charger's cell (charging(a) only).
  planner::Vertex goal(int a) const { return chargers_[claim_[a]].cell; }
  bool low(int a) const { return charge_[a] < options_.threshold * options_.capacity_wh || short_of_reserve(a); }
  // So low that a task in hand must wait (charging on): the agent charges first.
  bool critical(int a) const
  {
    return options_.charging && (charge_[a] < options_.critical * options_.capacity_wh || short_of_reserve(a));
  }
  // Below the reserve at its cell of the last step() (reserve_margin > 0, charging on).
  bool short_of_reserve(int a) const;
  // The energy (Wh) of the shortest way from `v` to charger i (turns included, see above).
  double way_wh(int i, planner::Vertex v) const { return way_wh_[i][v]; }
  long long swaps() const { return swaps_; }  // claims swapped (rematch)
  // Low with charging on: it takes no task until it has charged.
  bool wants(int a) const { return options_.charging && (low(a) || first_[a]); }
  // The task check (above): can agent a drive `moves` moves and then, from `last`, reach the
  // nearest charger, with the reserve margin? Always true with the reserve or charging off.
  bool affords(int a, long long moves, planner::Vertex last) const;
  // The most one move can drain: per_m_wh x the longest arc + per_turn_wh.
  double move_wh() const { return move_wh_; }
  // Agent a could not afford the task it was matched with: it charges before it takes one
  // (wants() until it leaves a charger). False (nothing done) when it is charged to target.
  bool charge_first(int a);
  bool is_charger(planner::Vertex v) const { return charger_of_[v] >= 0; }
  // A charger and, at a dead end, the corridor cells that lead to it: an idle agent resting
  // there would block the way in (the TaskManager's parking keeps idle agents off them).
  bool reserved(planner::Vertex v) const { return reserved_[v] != 0; }
  // Charger i stands at a dead end; else traffic may push a charging agent off it (it then
  // gains nothing until it is back).
  bool dead_end(int i) const { return dead_end_[i] != 0; }

  const BatteryOptions& options() const { return options_; }
  const std::vector<Charger>& chargers() const { return chargers_; }
  double charge(int a) const { return charge_[a]; }  // Wh
  double min_charge() const { return min_fraction_; }  // the lowest any agent had, fraction of capacity
  const std::vector<double>& charges() const { return charge_; }
  int ran_empty() const { return ran_empty_; }
  bool empty(int a) const { return empty_[a] != 0; }
  const std::vector<int>& emptied() const { return emptied_; }  // agents that ran empty in the last step()
  long long errands() const { return errands_; }              // charging errands begun
  long long charging_ticks() const { return charging_ticks_; }  // agent-steps standing on a charger gaining charge
  long long agent_ticks() const { return agent_ticks_; }       // agent-steps counted

 private:
  int nearest_free(planner::Vertex from);  // a charger index, -1: none free
  // At target: charging ends, and no task check or charge_first() applies.
  bool at_target(int a) const { return charge_[a] >= options_.target * options_.capacity_wh - 1e-9; }
  void plan_ways();                        // way_m_, way_wh_ (the reserve, rematch)
  void rematch(const planner::Config& positions);

  const planner::Graph& g_;
  BatteryOptions options_;
  std::vector<Charger> chargers_;
  std::vector<std::pair<double, double>> xy_;
  std::vector<int> charger_of_;  // per vertex: charger index, -1
  std::vector<uint8_t> reserved_;  // per vertex: a charger or its dead-end corridor
  std::vector<char> dead_end_;     // per charger
  std::vector<int> claimed_by_;  // per charger: agent, -1
  std::vector<std::vector<double>> way_wh_;  // per charger, per vertex: energy of the way there (reserve)
  std::vector<std::vector<double>> way_m_;   // per charger, per vertex: metres of the way there (rematch)
  long long swaps_ = 0;
  std::vector<double> charge_;
  std::vector<char> first_;      // per agent: charge_first() until it leaves a charger
  double move_wh_ = 0;
  std::vector<int> claim_;       // per agent: charger index, -1
  std::vector<char> empty_;
  std::vector<int> emptied_;
  std::vector<double> dir_x_, dir_y_;  // per agent: direction of its last move (0, 0: none yet)
  planner::Config last_;
  std::vector<int> seen_;
  int stamp_ = 0;
  int ran_empty_ = 0;
  double min_fraction_ = 1;
  long long errands_ = 0, charging_ticks_ = 0, agent_ticks_ = 0;
};

}  // namespace tasks
