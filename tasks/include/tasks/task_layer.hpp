#pragma once
// The task layer of a lifelong run, built once for every front end: the SUMO controller's
// YAML (controller/src/lifelong.cpp), rtlacam-lifelong's command line (apps/) and Python's
// keyword arguments (python/src/module.cpp) each only fill TaskLayerOptions; make_task_layer
// builds the mode and sets its options in one order. The option structs of the parts are
// held whole (QueueOptions, UrgencyOptions, ParkingOptions, BatteryOptions), so a field
// added to one of them reaches every front end that fills it, with no copy in between.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "planner/graph.hpp"
#include "tasks/battery.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/parking.hpp"
#include "tasks/station_queues.hpp"
#include "tasks/task_manager.hpp"
#include "tasks/urgency.hpp"

namespace tasks {

// Batteries (battery.hpp), off unless `on`. The chargers either as a back end measured them
// (`chargers` with every cell's centre `xy` in metres: SUMO), or, with `xy` empty, on a grid
// map (TaskManager::set_grid_battery): a charger on each of `charger_cells`, `charge_w` watts
// for 1 s steps.
struct BatterySetup {
  bool on = false;
  BatteryOptions options;
  std::vector<Charger> chargers;
  std::vector<std::pair<double, double>> xy;
  std::vector<planner::Vertex> charger_cells;
  double charge_w = 7200 * 0.95;  // the shipped chargingStations' power x efficiency
};

struct TaskLayerOptions {
  std::string mode = "roundrobin";  // roundrobin | pool
  std::string assigner = "greedy";  // pool: greedy | hungarian
  int k_nearest = 32;               // hungarian: candidate tasks per agent
  int pool_size = 0;                // pool: revealed tasks at once (> 0; each front end has its default)
  bool reassign = false;            // pool: a nearer free agent may take a task not yet opened
  QueueOptions queues;
  UrgencyOptions urgency;
  ParkingOptions parking;
  BatterySetup battery;
};

// The first bad field of `o` as "key: what is wrong" ("" when fine), with the YAML's key
// names under tasks (mode is tasks.assignment there); the battery is checked when it is set
// ("battery.key: what", battery_problem's keys, or battery.chargers / battery.charge_w).
std::string task_layer_problem(const TaskLayerOptions& o);

// The task manager of `file` on `g` (the agents' graph) with o's parts set, before its
// start(). std::invalid_argument with task_layer_problem()'s message, or the battery's.
std::unique_ptr<TaskManager> make_task_layer(std::shared_ptr<const TaskFile> file, const planner::Graph& g,
                                             const TaskLayerOptions& o);

}  // namespace tasks
