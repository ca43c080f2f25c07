#pragma once
// QueueTrace: what every station queue holds, every N steps, as text (output.queue_trace).
//
// Why: a station that stops serving is invisible in the totals until throughput sags, and
// its cause is local: who stands in its stub, on its lane, and where its admitted agent is.
// This trace found the lane tangles of the 1000-AGV epibt runs (session 39: agents that had
// just left drop31 stood in its queue lane with their next errands elsewhere, between its
// admitted AGV and the mouth; no errand there for 2246 ticks).
//
// One line per station per snapshot:
//   t station cell (x,y) done D admitted[A ...] waiting W pocket[A ...] queue[A|- ...]
// D: errands completed at the station since the last snapshot; W: agents holding a queue
// place there; pocket: everyone standing in the station's dead-end stub (or on the station);
// queue: the queue cells from the one beside the mouth outwards, "-" where nobody stands.
// An agent is written `id@cell` and a state: H<errand cell>s<stall> heading for its errand
// (its longest stall so far, errand_stalls.hpp), Q<errand cell> queued or parked with a task,
// I idle. Cells are vertex ids; (x,y) is the grid cell where the graph has a grid view.
#include <cstdio>
#include <string>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"
#include "tasks/task.hpp"

namespace tasks {

class TaskManager;

class QueueTrace {
 public:
  // Opens `path` for writing; a snapshot every `every` steps (>= 1). A failed open or write
  // throws planner::OutputError "cannot write 'PATH': reason" (planner/output_file.hpp).
  QueueTrace(const std::string& path, int every, const planner::Graph& g);
  ~QueueTrace();
  QueueTrace(const QueueTrace&) = delete;
  QueueTrace& operator=(const QueueTrace&) = delete;

  // After the task layer's update at step t: counts `completed`, and writes a snapshot when
  // t is a multiple of `every`. Without station queues it writes nothing.
  void step(long t, const TaskManager& tm, const planner::Config& positions, const std::vector<Event>& completed);

 private:
  std::string who(const TaskManager& tm, long t, int agent, planner::Vertex at) const;
  std::string cell(planner::Vertex v) const;
  void write(const std::string& text) const;
  [[noreturn]] void fail() const;

  std::string path_;
  std::FILE* f_ = nullptr;
  int every_;
  const planner::Graph& g_;
  std::vector<int> done_;                            // per station, since the last snapshot
  std::vector<std::vector<planner::Vertex>> pocket_;  // per station: its stub cells
  std::vector<int> at_;                              // per vertex: the agent standing there, -1
};

}  // namespace tasks
