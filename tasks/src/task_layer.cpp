#include "tasks/task_layer.hpp"

#include <stdexcept>

#include "tasks/assigner.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/task_pool.hpp"

namespace tasks {

std::string task_layer_problem(const TaskLayerOptions& o)
{
  if (o.mode != "roundrobin" && o.mode != "pool") return "assignment: must be roundrobin or pool, not '" + o.mode + "'";
  if (o.mode == "pool") {
    if (o.assigner != "greedy" && o.assigner != "hungarian")
      return "assigner: must be greedy or hungarian, not '" + o.assigner + "'";
    if (o.pool_size < 1) return "pool_size: must be >= 1, got " + std::to_string(o.pool_size);
    // The YAML's and numTasksReveal x teamSize's bound: the pool reserves its tasks up front.
    if (o.pool_size > 10000000) return "pool_size: must be at most 10000000, got " + std::to_string(o.pool_size);
    if (o.k_nearest < 1) return "k_nearest: must be >= 1, got " + std::to_string(o.k_nearest);
  }
  const QueueOptions& q = o.queues;
  if (q.capacity < 0) return "queues.capacity: must be >= 0, got " + std::to_string(q.capacity);
  if (q.length < 0) return "queues.length: must be >= 0, got " + std::to_string(q.length);
  if (q.admission < -1 || (q.admission > 0 && q.admission < q.capacity))
    return "queues.admission: must be >= capacity (" + std::to_string(q.capacity) + "), 0 or -1, got " +
           std::to_string(q.admission);
  return "";
}

std::unique_ptr<TaskManager> make_task_layer(std::shared_ptr<const TaskFile> file, const planner::Graph& g,
                                             const TaskLayerOptions& o)
{
  if (const std::string why = task_layer_problem(o); !why.empty()) throw std::invalid_argument(why);
  std::unique_ptr<TaskManager> tm;
  if (o.mode == "roundrobin")
    tm = std::make_unique<RoundRobin>(std::move(file));
  else
    tm = std::make_unique<TaskPool>(std::move(file), g, o.pool_size, make_assigner(o.assigner, o.k_nearest), o.reassign);
  tm->set_queues(g, o.queues);
  tm->set_urgency(o.urgency);
  if (o.parking.on) tm->set_parking(g, o.parking.cells);
  const BatterySetup& b = o.battery;
  if (b.on) {
    try {
      if (b.xy.empty())
        tm->set_grid_battery(g, b.options, b.charger_cells, b.charge_w);
      else
        tm->set_battery(g, b.options, b.chargers, b.xy);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("battery.") + e.what());
    }
  }
  return tm;
}

}  // namespace tasks
