#pragma once
// Escalation: a starvation guard for lifelong errands (issue 24: "errands never stalling more
// than K ticks"; UrgencyOptions::escalate_after, 0 = off).
//
// The other stall rules order a crowd (urgency.hpp); none of them promises the errand that
// keeps losing anything. Traced on small_rules_lifelong (session 38, 16 AGVs, no queues, 1000
// ticks, K 505): a drop errand for drop3 swept back and forth with three other AGVs along the
// one-cell cross aisle west of it for 505 ticks -- head-on AGVs take turns pushing each other,
// PIBT's priorities reset at every epoch, and RT-LaCAM's epoch ends whenever anyone arrives,
// so nobody plans the way out for that one errand.
//
// An errand escalates once its holders have headed for its cell escalate_after steps since
// its last progress (TaskManager::escalated; steps waiting on a station's queue cells do not
// count: admission owns that wait, and counting it escalated every admitted AGV at a busy
// station), and stays escalated until it completes (a step of progress must not drop it
// behind the crowd again). Only one errand per errand cell, the longest-stalled (ties
// to the lower agent): one AGV at a time gets into a one-lane stub, and escalating every
// errand past 60 ticks on small_rules_lifelong jammed it (K 522-718, p99 516-569). While it
// heads for its cell:
//  - its holder gets kEscalatedUrgency + its stall (capped) as priority hint: above every
//    stall hint, below battery urgency and agents leaving a pocket (kLeavingUrgency, since
//    session 42); the longest-stalled first;
//  - the epoch's goal test waits for the longest-stalled escalated agent off its goal
//    (lifelong_goal.hpp), as for a low battery, so RT-LaCAM plans a way for it, not for
//    whoever arrives first (for any escalated agent: three of them head-on at one junction
//    jammed small_rules_lifelong, seed 3, 4000 ticks, K 904 against 450);
//  - the dead-end pocket of its errand cell is cleared for it: every other agent standing in
//    that pocket whose goal is outside it gets kClearingUrgency (above the escalated one and
//    above a low battery: in a one-lane stub the way in is the way out. An escalated AGV
//    wedged in front of an occupant jammed small_rules_lifelong on 5 of 10 seeds, K 395-913;
//    low AGVs pushing in past the leaver jammed small_charging_lifelong, seed 2, K 2018), and
//    an idle agent standing there gets a goal outside (evict_cell), kept until it arrives or
//    gets a task.
// Hints alone K 335, the goal test alone K 706, both K 175 (seed 1). An errand waiting on a
// station's queue (not heading) gets none of this: admission is the queues' (clear_after,
// leavers_first). Hints only order conflicts and the goal test stays one complete search, so
// the planners' guarantees hold as with battery urgency.
//
// Off by default; shipped in small_rules, small_oneway and small_charging_lifelong, where it
// bounds K (small_rules: K max 226 over 20 seeds at 10000 ticks; controller/README.md
// "Session 41"). Mixed on the large parking and queue examples (pibt-rot on
// large_warehouse_queues: 0.91x errands at 4000 ticks), so not a default.
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace tasks {

class TaskManager;

inline constexpr float kEscalatedUrgency = 6000.0f;  // + min(stall, kEscalatedSpan - 1)
inline constexpr float kEscalatedSpan = 3000.0f;
inline constexpr float kClearingUrgency = 25000.0f;  // leaving an escalated errand's pocket: above battery urgency (<= 20000)

// Per agent, 1 where it holds an escalated errand (above); empty when off or none.
std::vector<char> escalated_agents(const TaskManager& tm);

// The escalated agent an epoch waits for (lifelong_goal.hpp): the longest-stalled escalated
// holder heading for its cell and off it at `positions` (ties to the lower agent); -1 when
// none, while an agent low on charge is pending (battery urgency comes first), and on a
// directed graph (escalation.cpp: RT-LaCAM's one-way rule).
int escalation_focus(const TaskManager& tm, const planner::Config& positions);

// Raises h (one hint per agent) for the escalated errands whose holders head for their cells,
// and for the agents in their pockets bound outside.
void escalation_hints(const TaskManager& tm, const planner::Config& positions, std::vector<float>& h);

// Per vertex: 1 in the dead-end pocket (TaskManager::dead_end_pockets) of the cell of an
// escalated errand whose holder heads for it; empty when none (`esc`: escalated_agents).
std::vector<char> escalated_pockets(const TaskManager& tm, const std::vector<char>& esc);

// Where an idle agent standing at `from` in such a pocket goes: the nearest cell (moves along
// arcs) outside every dead-end pocket, not next to one (a pocket's mouth carries its traffic)
// and not in `avoid` (queue cells; may be null); `from` when none.
planner::Vertex evict_cell(const planner::Graph& g, const std::vector<planner::Vertex>& dead_end_pocket,
                           planner::Vertex from, const std::vector<uint8_t>* avoid);

}  // namespace tasks
