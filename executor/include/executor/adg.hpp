#pragma once
// Adg: the action dependency graph of Hönig et al., "Persistent and Robust Execution of
// MAPF Schedules in Warehouses" (RA-L 2019), built incrementally over the configurations a
// real-time planner commits.
//
// Every move of an agent between two committed configurations is an Action (waits are
// dropped: under delays, "wait one tick" has no meaning). Edges:
//   type 1: an agent's actions in plan order;
//   type 2: the action entering a cell v depends on the most recent earlier-or-same-step
//           action of ANOTHER agent that left v (the cell hand-over order of the plan).
// An action is released when all its dependencies are done; it is done when the agent
// has arrived (its whole body) on the target cell.
//
// Why the executed motion is collision-free: a cell is entered only after its previous
// occupant has arrived elsewhere (type 2; earlier occupants left before that one entered,
// by induction), and an agent's actions run in order (type 1). So at any time each cell is
// claimed by at most one agent (claims = the cell an agent stands on, or both ends of the
// move it is executing): no vertex conflict, no swap, no following into a moving body.
// The one exception is a running rotation group (below): its members share the ring's
// cells while they rotate together, and none leaves the ring before all have arrived.
// Why it never deadlocks under finite delays: dependencies point from plan step t to step
// t' >= t, so within a valid plan they form a DAG -- except rotation cycles (a->b->c->a in
// one step, which MAPF allows). Those are bound into one Group: its members are released
// together when the dependencies from outside the group are done, and start together; a
// member's next action waits until the whole group is done (members share cell claims
// while they rotate, so none may take part in anything else before the rotation ends).
// A DAG with finite delays always has an action whose dependencies are done, hence
// progress; with RT-LaCAM's completeness (it reaches the goals in finitely many commits)
// every committed step is eventually executed (tested in tests/executor/).
//
// append() only needs the plan to be valid (vertex/swap-free, moves along edges): the
// committed window may run ahead of execution by any amount, the ADG honours it.
//
// Bounded memory over lifelong runs: append() drops the done prefix once it holds at least
// kCompactMin actions and half of those stored -- whole plan steps only, so no rotation group
// is split. Action and group ids stay global (num_actions() counts every action ever
// appended); a reference to a dropped action (prev, handover, the cell's last leave) becomes
// -1, which every query already reads as "done", so decisions do not change (tested).
// action(id) is valid for id >= first_action(); last_done() is -1 once its action is dropped.
#include <cstdint>
#include <vector>

#include "planner/config.hpp"

namespace executor {

enum class State : uint8_t { Pending, Running, Done };

struct Action {
  int agent = -1;
  planner::Vertex from = -1, to = -1;
  long long step = 0;      // plan step: configuration `step` -> `step + 1`
  int prev = -1;           // type 1: the agent's previous action (-1: none)
  int handover = -1;       // type 2: the other agent's action leaving `to` (-1: none)
  int group = -1;          // rotation cycle this action belongs to (-1: none)
  State state = State::Pending;
};

class Adg {
 public:
  // compact_min: the done prefix dropped at least this large (tests use small values).
  explicit Adg(const planner::Config& start, int compact_min = kCompactMin);

  // Appends the step tail() -> next (a valid MAPF step). Returns the number of actions added.
  int append(const planner::Config& next);

  int num_agents() const { return static_cast<int>(tail_.size()); }
  long long steps() const { return steps_; }              // configurations appended
  const planner::Config& tail() const { return tail_; }   // last appended configuration
  const Action& action(int id) const { return actions_[id - base_]; }
  int num_actions() const { return base_ + static_cast<int>(actions_.size()); }
  int first_action() const { return base_; }  // ids below were done and dropped
  int stored_actions() const { return static_cast<int>(actions_.size()); }
  static constexpr int kCompactMin = 1 << 15;

  // The agent's first action not done (running or pending), -1 if none.
  int next_action(int agent) const;
  // Pending and every dependency done (for a group member: every member's outside
  // dependencies done).
  bool released(int id) const;
  // Moving-block following (GraphExecution "adg-follow"): a follower may start entering v
  // once the previous occupant has STARTED leaving v (its hand-over running or done), but
  // may only arrive (may_finish) once that one has arrived elsewhere. Safe on the MAPF
  // graph, where an agent occupies its source cell until it arrives: v is entered (occupied)
  // only after its previous occupant has left it, as with released(); the follower only
  // spends its travel time while the leader spends its own. Not for bodies with extent in
  // SUMO: there the follower's front would have to keep behind the leader's back.
  bool released_following(int id) const;
  bool may_finish(int id) const;
  // Pending -> Running; a group member starts its whole group. Throws if not released.
  void start(int id);
  void start_following(int id);  // throws unless released_following
  // Running -> Done.
  void finish(int id);
  // Chaining (a physical agent that need not stop between two moves): the agent's action
  // after its first undone one (-1 if none), and whether it may start before that one is
  // done: pending, neither it nor the running one in a group, its hand-over done -- the cell it enters is free; the
  // type-1 edge only orders the agent's own moves, which its motion along the path keeps.
  int chain_candidate(int agent) const;
  bool chainable(int id) const;
  void start_chained(int id);  // throws unless chainable
  // A replan (controller/stuck_replan.hpp) carries moves already running in the ADG it
  // replaces: they run on here without the release check (the old ADG released them under
  // its rule, and they keep their order); a rotation group resumes as one.
  void resume(int id);
  // Continuous motion (the SUMO Driver): the agent's k-th undone action (k = 0: next_action),
  // -1 if none; chaining any number of actions ahead of the running ones.
  int undone(int agent, size_t k) const;
  // Chaining with moving-block following: as chainable(), but the hand-over need only have
  // started (the previous occupant is leaving the cell); the caller keeps the body gap.
  bool chainable_following(int id) const;
  void start_chained_following(int id);  // throws unless chainable_following
  // The agent's last done action (-1 if none), and whether every member of group g is done.
  int last_done(int agent) const { return head_[agent] > 0 ? queue_[agent][head_[agent] - 1] : -1; }
  bool group_done(int g) const;
  // Switchable ADG (Berndt et al., "A Feedback Scheme to Reorder a Multi-Agent Execution
  // Schedule by Persistently Optimizing a Switchable Action Dependency Graph", 2020), in a
  // greedy form (adg_switch.cpp): action `id` (agent j entering v) waits for another agent
  // i's passage through v that i has not begun (its move into v pending and not released).
  // Then j passes v first: the order of the two passages through v is switched (i's entry
  // waits for j's leave of v; whoever followed j on v now follows i) -- only if j's leave of
  // v is appended, no rotation group takes part, and the ADG stays acyclic (checked by a
  // search over the undone actions). The cell order stays a total order per cell, so the
  // executed motion is collision-free as before (header comment). True if switched.
  // The rule (when a switch is worth trying; the acyclicity check is always made):
  struct SwitchRule {
    int lead = 1;              // i has at least this many undone moves before its move into v
    bool leader_at_rest = true;  // i is at rest (its next move pending)
    bool must_pass = true;       // the cell after v is being left already: j will not park on v
  };
  bool try_switch(int id, const SwitchRule& rule);
  bool try_switch(int id) { return try_switch(id, SwitchRule{}); }
  long long switches() const { return switches_; }
  // Members of the action's group (just the action itself when it has none).
  std::vector<int> group_of(int id) const;

  // Where the agent is for the plan: target of its last done action (or its start).
  planner::Vertex at(int agent) const { return at_[agent]; }
  // The plan step the agent's next undone action belongs to, steps() if it has none:
  // min over agents is how far execution has got into the committed window.
  long long progress(int agent) const;
  long long min_progress() const;
  // Every action appended is done (done_count_ counts them all, also those compact() dropped).
  bool done() const { return done_count_ == static_cast<long long>(num_actions()); }
  long long actions_done() const { return done_count_; }

 private:
  void run_group(int id);  // the action and its rotation group (if any) start running
  bool outside_deps_done(int id) const;
  // The type-1 dependency: the previous action done -- if it belongs to a rotation group,
  // the whole group (a member that arrives first does not leave its cell, still claimed by
  // the rotation, until every member has arrived).
  bool prev_done(int id) const;
  bool outside_deps_started(int id) const;
  bool dep_done(int dep) const { return dep < 0 || act(dep).state == State::Done; }
  Action& act(int id) { return actions_[id - base_]; }
  const Action& act(int id) const { return actions_[id - base_]; }
  const std::vector<int>& group(int g) const { return groups_[g - group_base_]; }
  void compact();  // drops the done prefix (see the header comment)
  bool depends_on(int from, int target) const;  // target reachable over dependencies (undone)

  planner::Config tail_, at_;
  std::vector<Action> actions_;
  std::vector<std::vector<int>> queue_;  // per agent: action ids in order
  std::vector<size_t> head_;             // per agent: index of its first undone action in queue_
  std::vector<int> last_leave_;          // per cell: last action that left it
  std::vector<std::vector<int>> groups_;  // group g at groups_[g - group_base_]
  int base_ = 0, group_base_ = 0;         // global ids of actions_[0] and groups_[0]
  int compact_min_;
  long long steps_ = 0, done_count_ = 0, switches_ = 0;
};

}  // namespace executor
