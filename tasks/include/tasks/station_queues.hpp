#pragma once
// StationQueues: admission control and queues at stations (issue 24, "parking and queues").
//
// A station is an errand cell. It admits at most `capacity` agents at once: only they head
// for its cell (their goal is the station, and only they are the epoch's pending agents:
// tasks/lifelong_goal.hpp); an agent still standing in the station's pocket (below) on its
// way out takes a place too, so the next one is let in only once the way is clear. The
// next agents with an errand there wait on the station's queue cells in order (q1 nearest
// the station) and move up as the queue moves; any further ones are `unplaced` and wait
// like idle agents (parking.hpp) until the queue has room. Places are sticky: an admitted agent keeps its place until its errand there
// completes, a queued one only moves up; newcomers are taken nearest first (graph
// distance to the station). Without this every agent with an errand at a station drives
// to it at once, and at a dead-end station the crowd in front of it blocks the way out of
// the one standing on it (the 1000-AGV lifelong jam, controller/README.md).
//
// Queue cells: a chain, each cell one move farther from the station (along arcs) than the
// one before, so a queue moves towards the station. The chain avoids the station's pocket
// -- the corridor cells (at most 2 neighbours) joined to it when that corridor has only
// one way out -- and the junction at the pocket's mouth: an agent leaving a dead-end
// station comes back the way it came, and a queue in the pocket would meet it head-on
// (no swaps: a deadlock). So the chain starts beside the mouth and goes along the longest
// corridor there (a picking aisle rather than the cross aisle, which carries the traffic;
// junctions only where no corridor goes on), never on another station, pocket or queue.
// Stations, pockets and queue cells are `reserved()`: idle agents do not rest there
// (tasks/parking.hpp). All queues are laid out at construction, stations in cell order.
//
// Admission order (`fifo`, default): an agent's request at a station is stamped when its
// errand there first comes up (requests of one apply() nearest first), and the agents not
// yet placed are taken oldest request first, so a newcomer nearer the station never
// overtakes one already waiting beyond the queue and every request is served after the
// ones before it. With `fifo` off they are ranked nearest first at every apply(): an agent
// far away may never get in while nearer ones keep coming. (With pool admission at its
// default nobody is beyond a queue and the two orders are the same.)
//
// Goals change only when the task manager calls apply() (its start() and update(), every
// step while queues are on: a way out that clears is no completion); the task manager
// then starts a new epoch if any goal changed (TaskManager::goals_changed).
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "planner/config.hpp"
#include "planner/dist_table.hpp"
#include "planner/graph.hpp"

namespace tasks {

struct QueueOptions {
  int capacity = 0;   // agents heading for one station at once; 0 = no queues
  int length = 4;     // queue cells per station (fewer where the net has no room), >= 0
  int admission = 0;  // pool mode: tasks held at once with an errand left at one station;
                      // 0 = capacity + its queue cells (nobody beyond the queue), -1 = no limit
  bool fifo = true;   // not yet placed: oldest request first (false: nearest first)
  // Pocket clearing (0: off): a dead-end station whose pocket has held an agent not admitted
  // there (one that must get out) for this many consecutive steps gives up its places: its
  // admitted and queued agents wait like agents beyond the queue (parked, off the reserved
  // cells) and nobody is admitted until the pocket is empty; requests keep their order
  // (fifo). In a one-lane dead end nobody passes anybody, so a leaver with the station's
  // AGV behind it and the queue behind that gets out only when they all back off; PIBT
  // never backs them off (they rank above an idle leaver), and a short real-time search does
  // not find the long retreat. Traced on the shipped queue configs (session 36): an idle AGV
  // pushed onto a dead-end station stood there the rest of the run with the station's
  // admitted AGV behind it and its queue behind that (K 594, 964).
  int clear_after = 0;
  // In line (off: false): every step the station's admitted agent (while it is outside the
  // pocket) and its queued agents are ranked by their distance to the station, nearest
  // admitted first, then the queue cells in that order. A queue lane is single file: an
  // agent cannot overtake the ones between it and the station, so places given in request
  // order (fifo) leave the admitted agent, or queue cell 0's, behind others that must let it
  // through first, and nobody there can move. Traced on large_warehouse_parking (session 36,
  // 2000-4000 ticks): drop15's admitted AGV stood 9 cells up its queue lane behind a queued
  // AGV and two leavers for 150+ ticks, with the station free. Only the agents already placed
  // are re-ranked: the request order still decides who gets a place (fifo).
  bool in_line = false;
  // Leavers first while clearing (off: false; with clear_after): an agent in the pocket of a
  // clearing station on its way out gets the leaving priority (urgency.hpp, kLeavingUrgency)
  // whatever else the hints say. With queues `tasks.urgency.stalls` is on by default, and
  // stall hints skip the head hints' leaving rule, so the leaver ranked lowest: the AGVs
  // standing at the mouth and on the lane (unplaced ones of the station, idle ones, passers-by)
  // never made way for it. Traced on large_warehouse_parking (session 36, seed 4, 4000
  // ticks): drop15's stub held three AGVs with the mouth and the cells beside it full, and
  // clearing stayed on for the last 1143 steps. Only while a station clears: the leaving
  // priority for every pocket under stall hints cost throughput (session 36, dropped).
  // Measured there (s37, seeds 1-4, 4000 ticks): 1.02-1.05x errands/tick, K 348-906 against
  // 597-1221 (controller/README.md "Leavers first while clearing").
  bool leavers_first = false;
  // Idle agents keep clear of the mouths (off: false, the default for every solver): an idle agent (or one beyond its station's queue) rests neither on a
  // reserved cell nor on a cell beside a dead-end station's mouth (`clear_cells()`): there it
  // walls in the AGVs leaving the stub, which must then leave through the queue lane. Traced on
  // the huge warehouse twin with epibt (session 38): an idle robot shuttled in and out of a drop
  // stub for 1000 steps, the mouth's two cross-aisle neighbours held by idle robots resting on
  // their claims (an AGV that dropped in a stub claims the nearest unreserved cell: beside the
  // mouth). Huge twin, epibt, 5000 steps, p = 0.01: 1604 -> 1881 errands, last/first 1000
  // 0.67 -> 0.95; but in SUMO level (0.425 -> 0.427 errands/tick, last/first 0.77 -> 0.75) and
  // on the large_warehouse_queues twin at p = 0 worse (1454 -> 1153 errands), so not a default
  // (docs/twin_bench.md, session 38; session 36 found it mixed for pibt-rot on
  // large_warehouse_parking: controller/README.md, "Tried and dropped").
  bool idle_clear = false;
  // Jam clearing (0: off): a station whose admitted agent, outside the station's pocket, has
  // come no nearer to it (graph distance) for this many consecutive steps gives up its places
  // as pocket clearing does (clear_after): its admitted and queued agents wait parked, off the
  // reserved cells, until its pocket, mouth and queue cells hold nobody, or for this many
  // steps at most; requests keep their order (fifo). Why: a queue lane is a one-wide picking
  // aisle that other agents also cross. Traced in SUMO on the huge warehouse with epibt
  // (session 39, 1000 AGVs, p = 0.01): agents queued for other stations and idle ones stood
  // in drop31's lane between its admitted AGV and the mouth, its queue behind them, nobody
  // able to pass; the station made no errand for 2246 ticks. Queued agents stand on their
  // goals and rank high there, so epibt never backs the line off; giving up the places does.
  // Measured there (N = 100, four seeds): last/first 1000 ticks 0.69 -> 0.75 on average, one seed
  // worse (docs/twin_bench.md "Session 39"), so off by default.
  int jam_after = 0;
  // One-way queue lanes (off: false): the planners' graph has each station's queue lane
  // one-way towards the station (one_way_queue_lanes() below), so nobody walks a lane
  // against its queue. Why: a lane is a one-wide picking aisle, and the shortest way out of
  // a station after its errand often runs up that very aisle, head-on into the queue; queued
  // agents stand on their goals and rank high, so the one leaving (or a passer-by) is walled
  // in. Traced in SUMO on the huge warehouse with epibt (session 39, 1000 AGVs, p = 0.01):
  // agents that had just dropped at drop31 stood in its lane with their next errands
  // elsewhere, between its admitted AGV and the mouth, the queue behind them; the station
  // made no errand for 2246 ticks, and such jams piled up over the run. Measured there (four
  // seeds): worse on every seed (last/first 0.69 -> 0.61 on average): the upward traffic meets
  // the downward in the other aisles instead (docs/twin_bench.md "Session 39"), so off by default.
  bool one_way = false;
  bool on() const { return capacity > 0; }
};

// QueueOptions::in_line's default for a solver (the YAML's tasks.queues.in_line, rtlacam-lifelong's
// --queue-in-line and Python's queues): on for epibt, which cannot undo a one-wide queue lane out
// of request order (session 38, docs/twin_bench.md); request order for the others.
inline bool in_line_by_default(const std::string& solver) { return solver == "epibt"; }

// `g` with every station's queue lane one-way towards the station (QueueOptions::one_way): on a
// queue cell the only move is to the next cell towards the station (the mouth after q1), and
// the mouth no longer leads into q1; a lane is entered from its far end (or from the side)
// only. Stations, pockets and their lanes as StationQueues(g, stations, o) lays them out;
// vertices, positions, grid view and move costs are kept. Throws std::invalid_argument
// naming a station (`name`: how to name a cell to the user; default "cell <id>") if the
// result is not strongly connected (an errand could then be unreachable: a lane that is the
// only way between two parts of the net).
planner::Graph one_way_queue_lanes(const planner::Graph& g, const std::vector<planner::Vertex>& stations,
                                   const QueueOptions& o,
                                   const std::function<std::string(planner::Vertex)>& name = {});

class StationQueues {
 public:
  // `stations`: the errand cells (duplicates ignored).
  StationQueues(const planner::Graph& g, std::vector<planner::Vertex> stations, QueueOptions o);

  // errand[a]: agent a's next errand cell, -1 without a task. Rewrites goals[a] of the
  // queued agents; unplaced[a] (same size) is set for the agents beyond a queue, whose goal
  // the caller chooses (they wait like idle agents).
  void apply(const std::vector<planner::Vertex>& errand, const planner::Config& positions, planner::Config& goals,
             std::vector<char>& unplaced);

  const QueueOptions& options() const { return opt_; }
  int station_index(planner::Vertex v) const;  // -1: not a station
  int num_stations() const { return static_cast<int>(st_.size()); }
  planner::Vertex station(int i) const { return st_[i].cell; }
  // Where station i's queue starts from: its pocket's junction, or the station itself.
  planner::Vertex mouth(int i) const { return st_[i].mouth; }
  // The queue cells of station i, q1 first.
  const std::vector<planner::Vertex>& queue_cells(int i) const { return st_[i].queue; }
  // Pool admission: tasks held at once with an errand left at station i (-1: no limit).
  int admission_limit(int i) const;
  // The pocket cells of station i (the station itself at a through aisle or junction).
  int pocket_of(planner::Vertex v) const { return pocket_of_[v]; }
  bool reserved(planner::Vertex v) const { return reserved_[v] != 0; }
  const std::vector<uint8_t>& reserved_cells() const { return reserved_; }
  // Per vertex: reserved, or beside a dead-end station's mouth (a neighbour of the mouth
  // outside the pocket): where an idle agent must not rest with `idle_clear`.
  const std::vector<uint8_t>& clear_cells() const { return clear_; }
  // Agents admitted to station i now (heading for its cell).
  const std::vector<int>& admitted(int i) const { return st_[i].admitted; }
  const std::vector<int>& waiting(int i) const { return st_[i].waiting; }
  // Per vertex: the pocket, mouth and queue cells of the stations with an agent admitted or
  // queued (or clearing) at the last apply(): where an idle agent must not park (parking.hpp).
  const std::vector<uint8_t>& in_use_cells() const { return in_use_; }
  // Station i is clearing its pocket (clear_after): places given up until it is empty.
  bool clearing(int i) const { return st_[i].clearing; }
  // Times a station gave up its places to clear its pocket (clear_after).
  long clearings() const { return clearings_; }
  // Of those, jam clearings (jam_after).
  long jam_clearings() const { return jam_clearings_; }
  // Steps the stations spent clearing (summed over stations), and the longest clearing so
  // far in steps (one still going counts to now).
  long clearing_steps() const { return clearing_steps_; }
  int longest_clearing() const { return longest_clearing_; }
  void share_dist_cache(std::shared_ptr<planner::DistCache> cache) { dist_.share(std::move(cache)); }

 private:
  struct Station {
    planner::Vertex cell = -1;
    planner::Vertex mouth = -1;  // where the queue chain starts from: the pocket's junction, or the station
    int depth = 0;               // moves from the mouth to the station
    std::vector<planner::Vertex> queue;
    std::vector<int> admitted, waiting;
    int blocked = 0;        // consecutive apply() calls with a leaver in the pocket
    bool clearing = false;  // places given up until the pocket is empty (clear_after)
    int cleared_for = 0;    // apply() calls in the current clearing
    bool jam = false;       // the clearing is a jam clearing (jam_after)
    int jam_agent = -1;     // the admitted agent watched for progress (jam_after)
    int32_t jam_best = 0;   // its nearest distance to the station so far
    int jam_since = 0;      // apply() calls since it came nearer
  };
  void build_queue(Station& s);
  void drop_place(int agent);
  void in_line(int i, const planner::Config& positions);  // QueueOptions::in_line

  const planner::Graph& g_;
  QueueOptions opt_;
  std::vector<Station> st_;
  std::unordered_map<planner::Vertex, int> index_;
  std::vector<uint8_t> reserved_;  // per vertex: station, pocket or queue cell
  std::vector<uint8_t> clear_;     // clear_cells()
  std::vector<int> pocket_of_;     // per vertex: the station whose pocket it is in, -1
  std::vector<int> place_;         // per agent: station index it is admitted or queued at, -1
  std::vector<int> asked_at_;      // per agent: the station of its open request (fifo), -1
  std::vector<long> asked_;        // per agent: that request's stamp (a counter of requests)
  long requests_ = 0;
  long clearings_ = 0;
  long jam_clearings_ = 0;
  long clearing_steps_ = 0;
  int longest_clearing_ = 0;
  std::vector<uint8_t> in_use_;           // in_use_cells()
  std::vector<planner::Vertex> in_use_list_;  // its set cells
  std::vector<std::vector<planner::Vertex>> area_;  // per station: pocket, mouth and queue cells
  planner::DistTable dist_;        // distances to stations (ranking newcomers)
};

}  // namespace tasks
