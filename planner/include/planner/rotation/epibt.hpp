#pragma once
// Epibt (solver `epibt`): EPIBT, PIBT with multi-action operations (Yukhnevich &
// Andreychuk, "Enhancing PIBT via Multi-Action Operations", AAAI-26, arXiv 2511.09193; a
// LoRR 2024 entrant), for robots with a heading (LoRR's MAPF_T: F, R, C, W). Written anew
// from the paper's description and its public code (github.com/Straple/EPIBT, MIT; read
// in the fork github.com/lunjohnzhang/EPIBT, not copied); same interface and LoRR semantics as RotationPibt (rotation_pibt.hpp).
//
// Why: a one-step PIBT over rotation actions cannot see that a turn now pays off two steps
// later, and a robot pushed by a one-step PIBT must leave its cell in one step (with a
// heading it usually cannot). An *operation* is a sequence of `depth` actions (paper: 3,
// "FFF", "RFF", "WFW", ...); every robot holds one, and the operations of all robots are
// jointly conflict-free at every one of their time steps (no two robots on one cell, no two
// crossing one edge: following and cycles are allowed, as LoRR allows them).
//
// One step (EPIBT with operation inheritance, the paper's EPIBT(3) + IO):
//  - Each robot starts from the tail of last step's operation ("RFF" -> "FFW"): still
//    conflict-free, it is the robot's reservation until someone replans it.
//  - Robots in priority order: a robot r not yet touched this step drops its operation and
//    tries its candidates best first; a candidate whose cells/edges meet no one's is
//    taken; one that meets exactly one robot j of lower priority than the step's root
//    (priority inheritance) takes j's place and replans j recursively (j may not take back
//    what r now holds); on failure it is undone and the next candidate is tried. A robot
//    may be replanned at most `revisit` times per step (paper: 10; here 100, 10 in LNS); a robot that keeps
//    nothing new keeps its old operation. Robots already placed this step are final.
//  - Candidates: the paper's operation set (all F/R/C/W sequences of length `depth`, less
//    turns that end an operation, a turn undone before a forward, three equal turns; one
//    per (cells visited, final heading): 17 at depth 3), valid on the map (no F into a
//    wall), ranked by the steps to the goal: k if the operation first reaches the goal
//    cell after k actions, else depth + h(its end state) (RotationDist: exact, or weighted
//    if the tables ever are: only h values are compared, never a +1 per step assumed);
//    ties: more forward and earlier first (the paper's operation weight). WWW is not a
//    candidate (the paper: a robot keeps its old operation when nothing else fits), except
//    for a robot on its goal, and with `wait_op` on.
//  - Only the first action of each operation is executed; the rest is inherited.
//  - EPIBT+LNS (the paper's EPIBT_LNS; 20 rounds by default): rounds over the robots in
//    random order, each trying its candidates again without the priority rule, a change
//    kept only if the paper's weighted gain does not drop (docs/rotation_lorr.md "EPIBT").
// Priorities (`Priority::Distance`, the paper's): nearest to its goal first (h of the
// current state), ties by agent id; `Priority::Age`: RotationPibt's (steps since the goal
// was set, far first, dead-end boost).
//
// Like PIBT it is not complete (livelocks, e.g. in corridors); lifelong use tolerates it.
// search() plans once per step; with a time budget it stops replanning at the deadline
// (the robots not reached keep their inherited operations: still a valid step), so its
// decisions depend on timing only in steps that hit the deadline (counted: timeouts()).
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "planner/rng.hpp"
#include "planner/rotation/rotation_dist.hpp"
#include "planner/rotation/pocket_exit.hpp"
#include "planner/rotation/rotation_planner.hpp"
#include "planner/rotation/traffic_flow.hpp"

namespace planner {

struct EpibtOptions {
  enum class Priority { Distance, Age };
  int depth = 3;        // actions per operation (3..5; paper: 3; below 3 no half turn)
  // Replans of one robot per step at most (paper: 10). 100: with 10, two lines that meet
  // head-on in a one-wide corridor face each other for ever (each robot of the line that must
  // back out needs two turns first; the root's failing candidates use up the line's replans
  // before the chain that works is tried: test ALineBacksOutOfACorridorForALineFacingIt), which
  // took the 1000-AGV warehouse to 0.59-0.77 of its first 1000 ticks (docs/twin_bench.md
  // "Session 40").
  int revisit = 100;
  // The same limit in the LNS rounds (the paper's 10): LNS only improves a step that is valid
  // already, and at 100 its rounds cost 3x (MR23-I-08, 800 robots: CPU p50 22 -> 69 ms per step).
  int lns_revisit = 10;
  bool inherit = true;  // start each step from the tails of last step's operations (paper: IO)
  bool wait_op = false; // WWW among every robot's candidates (paper: only as the kept operation)
  Priority priority = Priority::Distance;
  // The pocket exit rule (needs set_pockets' labels, any cost): while a robot stands in a
  // dead-end pocket with its goal outside it, no operation moves anyone deeper into that
  // pocket. Why: in a one-wide station stub the next holder followed the leaving one in and
  // the queue behind it; the leaver, unable to push the whole line out, reversed (an off-goal
  // robot has no wait candidate) and the line followed it back: a livelock that took the
  // twins of the large and huge warehouses to 0-0.03 errands per step (s36 trace,
  // docs/twin_bench.md). Off: the paper's EPIBT.
  bool pocket_exit = true;
  // Leavers first (with pocket_exit): a robot that stands in a dead-end pocket with its goal
  // outside ranks above every other robot, so it may push the robots in the pocket and at
  // its mouth aside. Why: with the exit rule alone the robots bound for the station wait at
  // the mouth and, older than the leaver (its age restarted with its new goal), are never
  // pushed: large_warehouse_lifelong's twin fell to 0.27 of its first 1000 steps, the huge
  // one's to 0.37-0.63 (session 37, docs/twin_bench.md). Every leaver, unlike pibt-rot's
  // PocketExit::first (deep, crowded pockets only): limited so, the huge twin stayed at 0.56;
  // every leaver costs MR23-I-08 5 % (3.823 -> 3.631 errands/step).
  bool leavers_first = true;
  // EPIBT+LNS (the paper's EPIBT_LNS): after the pass, rounds in random order in which each
  // robot tries its candidates again, pushing anyone (no priority rule), kept only when the
  // weighted sum of the robots' gains does not drop. 0: off; -1: until the deadline (the
  // paper's; timing-dependent). 20 rounds: +6 to +75 % errands/step on MR23 at 0.2-26 ms
  // CPU per step (docs/rotation_lorr.md "EPIBT").
  int lns_rounds = 20;
  bool lns_converge = false;  // stop after a round that gained nothing (worse on 4 of 5 MR23)
  uint64_t seed = 0;  // LNS order
  // Online traffic-flow guide paths (traffic_flow.hpp; off by default): with it on, a robot
  // with a guide table ranks its operations by the congestion-aware h instead of the shared
  // goal table (priorities still use the shared one). Guide-path work runs at the start of
  // search(), within tf.share of the step's budget; robots whose table is not computed yet
  // use the shared goal table meanwhile.
  TrafficFlowOptions tf;
};

class Epibt : public RotationPlanner {
 public:
  using Options = EpibtOptions;
  using Priority = EpibtOptions::Priority;

  // All robots face `heading` (LoRR: east, 0) at the start. Needs a grid graph.
  Epibt(const Graph& g, const Config& starts, const Config& goals, Options opt = {}, GoalTest test = {},
        int heading = 0);

  // The operation set for `depth`, best first (the paper's weight: forward early); the
  // last entry is all waits. Exposed for tests.
  static std::vector<std::string> operations(int depth);

  Status search(const Budget& b) override;
  const Config& next() override;  // the cells after the first actions (turns keep the cell)
  void commit() override;
  void set_goals(const Config& goals, GoalTest test = {}) override;
  void set_max_dist_tables(size_t n) override { dist_.set_max_tables(n); }

  const Config& current() const override { return current_; }
  const Config& goals() const override { return goals_; }
  bool at_goal() const override { return passes_goal_test(test_, current_, goals_); }
  // Build calls (one robot trying its candidates), the unit between deadline checks: the
  // lifelong runner stops a search one average "expansion" early, which must not be a step.
  uint64_t expansions() const override { return calls_; }
  size_t explored() const override { return 0; }
  std::string name() const override { return "epibt"; }

  const std::vector<int>& headings() const override { return heading_; }
  const std::string& actions() const override { return action_; }  // one of "FRCW" per robot, after search()
  uint16_t h(int agent) const override { return dist_.get(goal_table_[agent], current_[agent], heading_[agent]); }
  const RotationDist& dist() const override { return dist_; }
  void prefetch(const std::vector<Vertex>& goals) override { dist_.prefetch(goals); }
  // Guide tables wanted (traffic flow) first, then the distance tables.
  bool precompute(std::chrono::steady_clock::time_point deadline) override;
  size_t pending() const override { return dist_.pending() + tf_queue_.size(); }
  void set_headings(const std::vector<int>& headings) override;
  void set_back_last(bool) override {}  // a RotationPibt option; operations decide how a robot yields
  // Guided: an operation costs the sum of its actions' costs (a quarter turn turn_cost, F
  // forward_cost(v, o), W the cheapest action) up to the goal, or all D + h(end state);
  // unguided every action costs 1, the paper's ranking.
  void set_guidance(Guidance gd) override;
  void set_deadline(RotationDist::Deadline d) override { dist_.set_deadline(d); }
  // Foreign pockets (RealtimePlanner::set_pockets, tasks.urgency.pocket_cost; RotationPibt's
  // rule): an operation whose F enters, from outside, a dead-end pocket other than the
  // robot's goal's ranks `cost` forward moves worse. Turns, waits and moves inside a pocket
  // are never charged; it only reorders candidates (a robot with no other way still takes
  // the stub). Empty or 0: off (unchanged decisions). Why: an idle robot pushed into a
  // one-cell station stub traps the holders bound there (docs/twin_bench.md, s34 trace).
  void set_pockets(std::vector<Vertex> pocket, float cost) override;

  // The operation each robot holds (after search(): the planned one), e.g. "RFF".
  std::string operation(int agent) const { return ops_[static_cast<size_t>(op_[agent])].acts; }
  const Options& options() const { return opt_; }
  // New options: every robot's operation becomes WWW (lifelong runs set them before step 1).
  void set_options(const Options& opt);
  uint64_t timeouts() const { return timeouts_; }  // steps whose replanning the deadline cut short
  uint64_t lns_rounds() const { return lns_rounds_done_; }
  const TrafficFlow* traffic_flow() const { return tf_.get(); }  // null when off
  size_t tf_pending() const { return tf_queue_.size(); }       // robots waiting for a guide table

 private:
  static constexpr double kLeaverKey = 1e9;  // leavers_first: above any age or -distance
  struct Op {
    std::string acts;
    int next;  // the operation that is this one's tail plus a wait ("RFF" -> "FFW")
  };
  enum Result { Failed, Accepted, Rejected };

  bool walk(int i, int op, Vertex* cells, int32_t* edges, int* end_heading) const;  // false: F into a wall
  void candidates(int i);  // cand_ of agent i for this step, best first
  int conflict(int i) const;  // the one robot i's path meets, -1 none, -2 several
  void place(int i);
  void unplace(int i);
  void set_op(int i, int op);
  Result build(int i, double root_key, bool lns);
  bool enters_blocked_pocket(int i, const Vertex* cells) const;  // pocket_exit: cells after each action
  void lns();
  void tf_reset();                  // (re)creates tf_ and queues every robot
  void tf_work(Clock::time_point deadline);  // queued guide tables, then refreshes

  const Graph& g_;
  Options opt_;
  std::vector<Op> ops_;
  int wait_ = 0;  // index of WWW in ops_
  bool guided_ = false;
  uint32_t wait_cost_ = 1;  // guided: the cheapest action
  mutable RotationDist dist_;
  Config current_, goals_, next_;
  std::vector<int> heading_;
  GoalTest test_;
  std::vector<RotationDist::Table*> goal_table_;
  std::vector<int> op_;             // per agent: its operation
  std::vector<Vertex> cells_;       // agent * depth + d: its cell after d + 1 actions
  std::vector<int32_t> edges_;      // agent * depth + d: the edge it crosses in action d, -1 none
  std::vector<int32_t> used_cell_;  // cell * depth + d -> agent or -1
  std::vector<int32_t> used_edge_;  // (min cell * 2 + axis) * depth + d -> agent or -1
  std::vector<double> key_;         // priority: larger first
  std::vector<double> age_;         // Priority::Age: RotationPibt's priority
  std::vector<int32_t> order_;
  std::vector<Vertex> pocket_;      // vertex -> its dead-end pocket, or -1 (set_pockets)
  float pocket_moves_ = 0;          // foreign-pocket cost in forward moves (0: off)
  PocketExit exit_;                 // the exit rule's depths and this step's leaving pockets (set_pockets)
  std::vector<uint8_t> cand_;       // agent * ops: candidate operations, best first
  std::vector<uint32_t> score_of_;  // agent * ops: cost * ops + op (lower better), valid operations
  std::vector<double> power_;       // LNS: weight of a robot's gain (priority rank, squared)
  double score_ = 0;                // LNS: sum of power * (score_of(WWW) - score_of(op))
  bool scoring_ = false;
  double lns_floor_ = 0;
  uint64_t lns_rounds_done_ = 0;
  double gain(int i) const
  {
    const size_t m = ops_.size(), at = static_cast<size_t>(i) * m;
    return power_[i] * (static_cast<double>(score_of_[at + static_cast<size_t>(wait_)]) - score_of_[at + static_cast<size_t>(op_[i])]);
  }
  Rng rng_{0};
  std::vector<uint8_t> ncand_;
  std::vector<uint32_t> cand_stamp_, visited_, placed_;
  std::vector<int> visits_;
  uint32_t stamp_ = 0;  // step: candidates
  uint32_t round_ = 0;  // pass or LNS round: visits
  std::chrono::steady_clock::time_point deadline_;
  uint64_t calls_ = 0;
  bool timed_out_ = false;
  std::string action_;
  bool planned_ = false;
  uint64_t steps_planned_ = 0, timeouts_ = 0;
  std::unique_ptr<TrafficFlow> tf_;
  std::deque<int32_t> tf_queue_;      // robots whose goal changed: guide table wanted
  std::vector<char> tf_queued_;
  size_t tf_next_ = 0;                // refresh: round robin over the robots
};

}  // namespace planner
