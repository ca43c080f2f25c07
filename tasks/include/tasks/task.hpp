#pragma once
// Task, errand and event: the plain data of the lifelong layer.
//
// A task is a sequence of errand cells (LoRR 2023: one errand per task; 2024: pick-up then
// drop, 2..5 errands). An errand completes when the agent holding the task stands on the
// errand's cell at the end of a step; at most one errand per agent per step, as in the
// LoRR start kits. A task is finished when its last errand completes.
#include <vector>

#include "planner/graph.hpp"

namespace tasks {

using planner::Vertex;

struct Task {
  long id = -1;                 // sequence number in the (cyclic) task stream: unique per run
  int line = -1;                // index of the task in the task file (id mod file size)
  std::vector<Vertex> errands;  // errand cells as graph vertices
  int next = 0;                 // index of the next errand to complete
  int agent = -1;               // holder, -1 while unassigned

  bool opened() const { return next > 0; }  // first errand done: cannot be reassigned
  bool finished() const { return next >= static_cast<int>(errands.size()); }
  Vertex next_cell() const { return errands[next]; }
};

// One completed errand: [t, agent, task, errand] in the JSON log.
struct Event {
  long t = 0;      // step at whose end the errand completed (first step = 1)
  int agent = -1;
  long task = -1;  // Task::id
  int errand = -1; // index within the task
  bool operator==(const Event& o) const { return t == o.t && agent == o.agent && task == o.task && errand == o.errand; }
};

// A task as revealed (for the LoRR log's `tasks`): sequence id, file line, step revealed.
struct TaskRecord {
  long id = -1;
  int line = -1;
  long revealed = 0;  // 0 = at the start, t = at the end of step t
};

// An agent's task changed at the end of step t (0 = start): `task` = Task::id, -1 = none.
struct Assignment {
  long t = 0;
  int agent = -1;
  long task = -1;
};

}  // namespace tasks
