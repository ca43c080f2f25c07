#pragma once
// Urgency: the task layer's priority hints for the planner (issue 24: errands that never
// stall more than K ticks; no AGV running empty).
//
// PIBT's elapsed-time priority (Okumura et al., AIJ 2022) makes an agent that waits win
// conflicts until it moves on; it resets at each new goal, and with keep_priorities off at
// each lifelong epoch, which on a crowded net starts every few ticks. An errand whose holder
// keeps losing conflicts then never gets done (large_oneway_lifelong, session 31: 135 of 200
// AGVs never completed an errand in 500 ticks, K 494). The task layer knows what the
// planner forgets: how long each errand has stalled (errand_stalls.hpp) and which agents
// are low on charge (battery.hpp). At each epoch start it hands the planner one number per
// agent, RealtimePlanner::set_priority_hint, a floor under its PIBT priority
// (planner/lacam/priority.hpp, raise_to_hint):
//  - stalls: a busy agent heading for its errand cell (not one waiting on a queue cell) gets
//    the ticks its errand has gone without getting closer (ErrandStalls::stalled);
//  - battery: an agent on its way to a charger, or holding a task while low (below the
//    threshold or the distance-aware reserve), gets kBattery + kBattery x (1 - its charge
//    fraction): above every stall, and the emptier one first (two low AGVs head-on: one
//    yields, they no longer swap priorities and oscillate);
//  - leavers first while clearing (StationQueues' QueueOptions::leavers_first): an agent in
//    the pocket of a station that is clearing it, on its way out, gets kLeavingUrgency;
//  - escalation (escalate_after, escalation.hpp): per errand cell the errand stalled longest,
//    past escalate_after ticks, gets kEscalatedUrgency + its stall (above the rest, below
//    battery) and the epoch's goal test.
// Hints only order conflicts; the planners' guarantees stay (RT-LaCAM's tree of an epoch is
// one complete search whatever the root's priorities). Battery urgency also narrows the
// epoch's goal test to the low agents (battery_urgent, below): still one complete search,
// for a goal that one agent reaching its charger satisfies.
#include <vector>

#include "planner/realtime_planner.hpp"

namespace tasks {

class TaskManager;

struct UrgencyOptions {
  bool stalls = false;   // hint stalled errands (needs TaskManager::watch_stalls)
  bool battery = false;  // hint low agents (needs a battery)
  // Stall handover (pool mode, needs watch_stalls; 0: off): an errand not yet opened that
  // has stalled this many ticks passes to a nearer agent heading for the same cell, which
  // takes over its task while the stalled agent takes the nearer one's (task_pool.hpp,
  // TaskPool::hand_over_stalled). Not a hint: no goal changes, the planner sees nothing.
  int swap_after = 0;
  // Head hints (0: off; ignored while `stalls` hints every stalled errand): per errand cell,
  // only the heading agent whose errand has stalled longest, if >= head_after ticks, gets
  // its stall ticks as a hint -- first come, first served per station, where hinting every
  // stalled agent wedges the crowd into the dead-end stubs (0.05 errands/tick against 0.80
  // on large_warehouse_lifelong). Pair it with swap_after: the handover keeps the most
  // stalled pick-up errand on the agent nearest its station, so the hinted head is at the
  // front of the crowd, not behind it (alone, head hints cost 40-60 % of the throughput).
  // Inside a station's dead-end pocket (TaskManager::pocket) nobody can pass anybody: an
  // agent heading in there gets no hint, and one on its way out of a pocket gets
  // kLeavingUrgency, so the agents behind it back out instead of wedging it in (traced:
  // a hinted AGV one cell before its drop station for 343 ticks, the AGV on the station
  // unable to leave).
  int head_after = 0;
  // Station load in the pool's matching (0: off): a task costs, besides its moves, this many
  // moves per task already held with an errand left at each of its remaining errand cells.
  int load_cost = 0;
  // Foreign-pocket cost (0: off; needs watch_stalls): PIBT ranks an agent's move into a
  // station's dead-end stub (TaskManager::dead_end_pockets) that is not its errand's this many
  // moves worse (RealtimePlanner::set_pockets). Traced on large_oneway_lifelong: a two-way
  // cross aisle between one-way picking aisles is a corridor whose only side cells are
  // the stubs, so head-on AGVs pushed each other into other stations' stubs (three AGVs
  // bound elsewhere filling one station's stub, its own AGVs stalled outside). Only orders
  // PIBT's candidates: a foreign stub stays a last resort, and the search stays complete.
  int pocket_cost = 0;
  // Drop hints (with head_after; off by default): every agent carrying a load (its task
  // opened, so the handover cannot pass the errand on) whose drop errand stalled >= head_after
  // ticks gets its stall ticks as a hint, not only the head of its drop station's crowd.
  // Traced on large_oneway_lifelong at 500-1000 ticks: every stall >= 100 ticks was a drop
  // errand held in head-on traffic on a two-way cross aisle, far from its station, where
  // "one head per station" left all but one of them without priority.
  bool drop_hints = false;
  // Sticky stalls (off by default): the hints and the handover read an errand's longest stall
  // so far (ErrandStalls::stalled), not only the current one. An errand that once waited long
  // and then moved a cell starts again from 0 without it, behind every newer stalled errand,
  // and can stall again and again (traced: the longest errand then never finished in the
  // run; with sticky stalls it did, s34-24c).
  bool sticky = false;
  // Escalation (0: off; needs watch_stalls): per errand cell, the errand whose longest stall
  // so far reached this many ticks gets the planner's top priority below battery urgency and
  // the epoch's goal test until it completes (escalation.hpp: the starvation guard).
  int escalate_after = 0;
  bool on() const { return stalls || battery || head_after > 0 || escalate_after > 0; }
};

inline constexpr float kBatteryUrgency = 10000.0f;

// Battery urgency on and agent a on its way to a charger, or busy while low. While such an
// agent is off its goal, the epoch's goal test (lifelong_goal.hpp) waits for one of them:
// a hint orders PIBT's conflicts, but RT-LaCAM follows the path to the first configuration
// that passes the goal test, and with "any pending agent arrives" that path may drag a low
// AGV up and down an aisle while another one arrives (bench_charging.py seed 2: three AGVs
// in one aisle for 40 ticks, one ran empty).
bool battery_urgent(const TaskManager& tm, int a);

// One hint per agent at the last update() (empty when every option is off). `positions`
// (where the agents stand; head hints need them) may be omitted by callers without head hints.
std::vector<float> priority_hints(const TaskManager& tm, const planner::Config* positions = nullptr);

// Agents leaving a dead-end pocket (head hints): above every stall and above battery urgency
// (<= 20000); a battery hint never lowers it. In a one-lane stub the way in is the way out: a
// low AGV pushing in ahead of one that must leave wedges both. With leavers below battery
// urgency (5000, overwritten by a low leaver's battery hint) the large warehouse with 16
// charger stubs (config/large_charging_lifelong.yaml at 0.025 Wh/m) jammed once its AGVs
// turned low: every charger stub packed with three AGVs, 0.739 errands/tick against 1.025
// without batteries; now 1.020 (controller/README.md "Session 42").
inline constexpr float kLeavingUrgency = 21000.0f;

// Hands p the dead-end pocket labels and pocket_cost (RealtimePlanner::set_pockets), also at
// cost 0: epibt's pocket exit rule needs the labels alone (every cost rule is off at 0).
void hint_pockets(const TaskManager& tm, planner::RealtimePlanner& p);

// Sets p's hints for its next epoch start (call right before set_goals / restart_at).
inline void hint_priorities(const TaskManager& tm, planner::RealtimePlanner& p)
{
  std::vector<float> h = priority_hints(tm, &p.current());
  if (!h.empty()) p.set_priority_hint(std::move(h));
  hint_pockets(tm, p);
}

}  // namespace tasks
