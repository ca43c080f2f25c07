#pragma once
// TaskFile builders independent of any file format: for task sources other than LoRR files
// (the SUMO controller's YAML task spec). Errand cells are graph vertices already.
#include <cstdint>
#include <string>
#include <vector>

#include "tasks/lorr_files.hpp"

namespace tasks {

// `count` random tasks of `errands` errands each: errand i is drawn uniformly from
// pools[i % pools.size()] (e.g. {pickups, drops}: pick-up, then drop). Deterministic for a
// seed on every platform (mt19937_64, explicit modulo). Throws std::invalid_argument when
// count < 1, errands < 1, pools is empty or a pool is empty.
TaskFile random_task_file(const std::vector<std::vector<planner::Vertex>>& pools, int count, int errands,
                          uint64_t seed, const std::string& name = "random");

// Tasks given as lists of errand cells (line = index). Throws std::invalid_argument when
// there is no task or a task has no errand.
TaskFile listed_task_file(std::vector<std::vector<planner::Vertex>> tasks, const std::string& name = "listed");

}  // namespace tasks
