#include "controller/lifelong.hpp"

#include <cmath>

#include "controller/fleet.hpp"
#include "tasks/task_builder.hpp"
#include "tasks/task_layer.hpp"

namespace controller {
namespace {

std::vector<planner::Vertex> errand_cells(const Config& cfg, const gridify::CellMap& map,
                                          const std::vector<CellRef>& refs, const std::string& key,
                                          const std::string& kind)
{
  std::vector<planner::Vertex> out;
  for (const CellRef& r : refs) out.push_back(resolve_cell(cfg, map, r));
  if (refs.empty()) {
    for (const gridify::Station& s : map.stations)
      if (s.kind == kind) out.push_back(s.cell);
    if (out.empty())
      throw ConfigError(cfg.path + ": " + key + ": missing, and " +
                        (cfg.sumo.additional.empty() ? std::string("there is no sumo.additional with stations")
                                                     : "sumo.additional has no station of kind '" + kind + "'"));
  }
  return out;
}

}  // namespace

std::vector<planner::Vertex> parking_cells(const Config& cfg, const gridify::CellMap& map)
{
  std::vector<planner::Vertex> out;
  if (!cfg.tasks.parking_auto) {
    for (const CellRef& r : cfg.tasks.parking_cells) out.push_back(resolve_cell(cfg, map, r));
    return out;
  }
  // A parkingArea on a lane gridify dropped is named, not silently lost.
  for (const gridify::Dropped& d : map.dropped)
    if (d.kind == "station" && d.reason.rfind("<parkingArea>", 0) == 0)
      throw ConfigError(cfg.path + ": tasks.parking: parkingArea '" + d.id + "' is on a lane gridify dropped (" + d.reason + ")");
  for (const gridify::Station& s : map.stations)
    if (s.element == "parkingArea") out.push_back(s.cell);
  if (out.empty())
    throw ConfigError(cfg.path + ": tasks.parking: true, but " +
                      (cfg.sumo.additional.empty() ? std::string("there is no sumo.additional") : "sumo.additional has no parkingArea"));
  return out;
}

std::vector<tasks::Charger> chargers(const Config& cfg, const gridify::CellMap& map)
{
  const FleetSection::Battery& b = cfg.fleet.battery;
  std::vector<tasks::Charger> out;
  for (const gridify::Dropped& d : map.dropped)
    if (d.kind == "station" && d.reason.rfind("<chargingStation>", 0) == 0)
      throw ConfigError(cfg.path + ": fleet.battery: chargingStation '" + d.id + "' is on a lane gridify dropped (" + d.reason + ")");
  for (const gridify::Station& s : map.stations) {
    if (s.element != "chargingStation") continue;
    const double w = s.power >= 0 ? s.power : b.charge_w;
    if (w < 0)
      throw ConfigError(cfg.path + ": fleet.battery: chargingStation '" + s.id +
                        "' has no power attribute and fleet.battery.charge_w is not set");
    for (const tasks::Charger& c : out)
      if (c.cell == s.cell)
        throw ConfigError(cfg.path + ": fleet.battery: chargingStations '" + c.id + "' and '" + s.id + "' are on one cell (" +
                          std::to_string(s.cell) + "): one AGV charges on a cell");
    out.push_back({s.cell, w * s.efficiency * cfg.run.tick_s / 3600.0, s.id});
  }
  if (out.empty() && b.charging)
    throw ConfigError(cfg.path + ": fleet.battery: charging is on, but " +
                      (cfg.sumo.additional.empty() ? std::string("there is no sumo.additional with a chargingStation")
                                                   : "sumo.additional has no chargingStation"));
  return out;
}

std::shared_ptr<const tasks::TaskFile> make_task_file(const Config& cfg, const gridify::CellMap& map)
{
  const TasksSection& t = cfg.tasks;
  if (!t.random_tasks) {
    std::vector<std::vector<planner::Vertex>> list;
    for (const std::vector<CellRef>& task : t.list) {
      std::vector<planner::Vertex> e;
      for (const CellRef& r : task) e.push_back(resolve_cell(cfg, map, r));
      list.push_back(std::move(e));
    }
    return std::make_shared<tasks::TaskFile>(tasks::listed_task_file(std::move(list), cfg.path + ": tasks.list"));
  }
  std::vector<std::vector<planner::Vertex>> pools;
  pools.push_back(errand_cells(cfg, map, t.pickups, "tasks.pickups", "pickup"));
  if (t.errands >= 2) pools.push_back(errand_cells(cfg, map, t.drops, "tasks.drops", "drop"));
  return std::make_shared<tasks::TaskFile>(
      tasks::random_task_file(pools, t.count, t.errands, t.seed, cfg.path + ": tasks.random"));
}

tasks::TaskLayerOptions task_layer_options(const Config& cfg, const gridify::CellMap& map)
{
  const TasksSection& t = cfg.tasks;
  tasks::TaskLayerOptions o;
  o.mode = t.assignment;
  o.assigner = t.assigner;
  o.k_nearest = t.k_nearest;
  o.pool_size = t.pool_size > 0 ? t.pool_size : static_cast<int>(std::ceil(1.5 * cfg.fleet.count));
  o.reassign = t.reassign;
  o.queues.capacity = t.queue_capacity;
  o.queues.length = t.queue_length;
  o.queues.admission = t.queue_admission;
  o.queues.fifo = t.queue_fifo;
  o.queues.clear_after = t.queue_clear_after;
  o.queues.jam_after = t.queue_jam_after;
  o.queues.one_way = t.queue_one_way;
  o.queues.in_line = t.queue_in_line;
  o.queues.leavers_first = t.queue_leavers_first;
  o.queues.idle_clear = t.queue_idle_clear;
  // tasks.urgency: stalls `auto` (-1) means on only with station queues (see config.hpp).
  o.urgency.stalls = t.urgency_stalls < 0 ? t.queue_capacity > 0 : t.urgency_stalls != 0;
  o.urgency.battery = t.urgency_battery;
  o.urgency.swap_after = t.urgency_swap_after;
  o.urgency.head_after = t.urgency_head_after;
  o.urgency.load_cost = t.urgency_load_cost;
  o.urgency.pocket_cost = t.urgency_pocket_cost;
  o.urgency.drop_hints = t.urgency_drop_hints;
  o.urgency.sticky = t.urgency_sticky;
  o.urgency.escalate_after = t.urgency_escalate_after;
  o.parking.on = t.parking;
  if (t.parking) o.parking.cells = parking_cells(cfg, map);
  const FleetSection::Battery& b = cfg.fleet.battery;
  o.battery.on = b.on;
  if (b.on) {
    tasks::BatteryOptions& x = o.battery.options;
    x.capacity_wh = b.capacity_wh;
    x.initial = b.initial;
    x.per_m_wh = b.per_m_wh;
    x.per_turn_wh = b.per_turn_wh;
    x.threshold = b.threshold;
    x.critical = b.critical;
    x.reserve_margin = b.reserve_margin;
    x.rematch = b.rematch;
    x.task_check = b.task_check;
    x.target = b.target;
    x.charging = b.charging;
    o.battery.chargers = chargers(cfg, map);
    for (const gridify::Cell& c : map.cells) o.battery.xy.emplace_back(c.x, c.y);
  }
  return o;
}

std::unique_ptr<tasks::TaskManager> make_task_manager(const Config& cfg, const gridify::CellMap& map,
                                                      std::shared_ptr<const tasks::TaskFile> file)
{
  try {
    return tasks::make_task_layer(std::move(file), map.graph, task_layer_options(cfg, map));
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();  // "battery.key: ..." is fleet.battery's, the rest tasks'
    throw ConfigError(cfg.path + ": " + (what.rfind("battery.", 0) == 0 ? "fleet." : "tasks.") + what);
  }
}

}  // namespace controller
