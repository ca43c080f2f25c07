#pragma once
// The task layer of a lifelong controller run (tasks.mode: lifelong), built from the YAML
// task spec: errand cells resolved on the gridified net (cell ids, station / junction ids,
// SUMO lane positions), random or listed tasks, then the tasks library's RoundRobin or
// TaskPool (tasks::make_task_layer, the one factory of every front end). Errors are
// ConfigErrors naming the key path.
#include <memory>

#include "controller/config.hpp"
#include "gridify/cell_map.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/task_layer.hpp"
#include "tasks/task_manager.hpp"

namespace controller {

// tasks.pickups / tasks.drops (default: the stations of kind pickup / drop), then
// tasks.random (errand i from pickups when i is even, from drops when odd) or tasks.list.
std::shared_ptr<const tasks::TaskFile> make_task_file(const Config& cfg, const gridify::CellMap& map);

// tasks.parking: the listed cells, or (true) the cells of the parkingAreas in
// sumo.additional; a parkingArea on a lane gridify dropped is an error naming it.
std::vector<planner::Vertex> parking_cells(const Config& cfg, const gridify::CellMap& map);

// fleet.battery: the chargingStations of sumo.additional as chargers (power x efficiency x
// tick_s per tick); errors name a station without power, one on a dropped lane, two on one
// cell, and charging on with no station.
std::vector<tasks::Charger> chargers(const Config& cfg, const gridify::CellMap& map);

// The YAML's task layer as tasks::TaskLayerOptions (tasks/task_layer.hpp): tasks.assignment,
// tasks.assigner, tasks.pool_size (0: ceil(1.5 x fleet.count)), tasks.k_nearest,
// tasks.reassign, tasks.queues, tasks.urgency (stalls auto: on with queues), tasks.parking
// and fleet.battery with the net's chargers and cell centres.
tasks::TaskLayerOptions task_layer_options(const Config& cfg, const gridify::CellMap& map);

// tasks::make_task_layer of those options; its errors as ConfigErrors naming the key.
std::unique_ptr<tasks::TaskManager> make_task_manager(const Config& cfg, const gridify::CellMap& map,
                                                      std::shared_ptr<const tasks::TaskFile> file);

}  // namespace controller
