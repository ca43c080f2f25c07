#include "tasks/queue_trace.hpp"

#include <cerrno>
#include <cstring>

#include "planner/output_file.hpp"
#include "tasks/station_queues.hpp"
#include "tasks/task_manager.hpp"

namespace tasks {

QueueTrace::QueueTrace(const std::string& path, int every, const planner::Graph& g)
    : path_(path), f_(std::fopen(path.c_str(), "w")), every_(every < 1 ? 1 : every), g_(g), at_(g.size(), -1)
{
  if (!f_) fail();
  write("# t station cell (x,y) done D admitted[...] waiting W pocket[...] queue[...]; agents id@cell "
        "H<errand>s<stall> heading, Q<errand> queued or parked with a task, I idle (tasks/queue_trace.hpp)\n");
}

void QueueTrace::fail() const
{
  throw planner::OutputError("cannot write '" + path_ + "': " + (errno ? std::strerror(errno) : "write failed"));
}

void QueueTrace::write(const std::string& text) const
{
  // Flushed at once: a full disk is an error now (planner/output_file.hpp's rule), not a
  // trace silently cut at the close.
  errno = 0;
  if (std::fputs(text.c_str(), f_) < 0 || std::fflush(f_) != 0) fail();
}

QueueTrace::~QueueTrace()
{
  if (f_) std::fclose(f_);
}

std::string QueueTrace::cell(planner::Vertex v) const
{
  std::string s = std::to_string(v);
  if (g_.is_grid()) s += " (" + std::to_string(g_.cell_x(v)) + "," + std::to_string(g_.cell_y(v)) + ")";
  return s;
}

std::string QueueTrace::who(const TaskManager& tm, long t, int a, planner::Vertex at) const
{
  std::string s = std::to_string(a) + "@" + std::to_string(at);
  if (!tm.busy(a)) return s + "I";
  const Task* k = tm.task_of(a);
  s += (tm.heading(a) ? "H" : "Q") + std::to_string(k->next_cell());
  if (tm.heading(a) && tm.stalls()) s += "s" + std::to_string(tm.stalls()->longest(t, k->id));
  return s;
}

void QueueTrace::step(long t, const TaskManager& tm, const planner::Config& positions, const std::vector<Event>& completed)
{
  const StationQueues* q = tm.queues();
  if (!q) return;
  if (pocket_.empty()) {
    pocket_.resize(q->num_stations());
    done_.assign(q->num_stations(), 0);
    for (planner::Vertex v = 0; v < g_.size(); ++v)
      if (q->pocket_of(v) >= 0) pocket_[q->pocket_of(v)].push_back(v);
  }
  for (const Event& e : completed)
    if (const int i = q->station_index(positions[e.agent]); i >= 0) ++done_[i];
  if (t % every_ != 0) return;
  for (size_t a = 0; a < positions.size(); ++a) at_[positions[a]] = static_cast<int>(a);
  std::string text;
  for (int i = 0; i < q->num_stations(); ++i) {
    std::string line = std::to_string(t) + " " + std::to_string(i) + " " + cell(q->station(i)) + " done " +
                       std::to_string(done_[i]) + " admitted[";
    for (int a : q->admitted(i)) line += " " + who(tm, t, a, positions[a]);
    line += " ] waiting " + std::to_string(q->waiting(i).size()) + " pocket[";
    for (planner::Vertex v : pocket_[i])
      if (at_[v] >= 0) line += " " + who(tm, t, at_[v], v);
    line += " ] queue[";
    for (planner::Vertex v : q->queue_cells(i)) line += " " + (at_[v] >= 0 ? who(tm, t, at_[v], v) : std::string("-"));
    text += line + " ]\n";
    done_[i] = 0;
  }
  for (planner::Vertex v : positions) at_[v] = -1;
  write(text);
}

}  // namespace tasks
