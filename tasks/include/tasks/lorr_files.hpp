#pragma once
// Readers for LoRR agent and task files.
//   agents: optional '#' comment lines, a count, then one cell id per line
//   tasks : the same header, then per line a comma-separated sequence of errand cells
// Cell id = row * width + column of the map. Every error is one line naming file:line:
// a count larger than the file, a bad number, an id off the map or on an obstacle.
#include <string>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace tasks {

// The first `team_size` agents' start vertices (all declared agents when team_size < 0).
// Also rejects two agents on one cell.
planner::Config load_lorr_agents(const std::string& path, const planner::Graph& g, int team_size = -1);

struct TaskFile {
  std::string path;
  std::vector<std::vector<planner::Vertex>> tasks;  // errand vertices per task
  std::vector<int> lines;                           // file line of each task
  int size() const { return static_cast<int>(tasks.size()); }
  // Every task's errand vertices in file order, repeats kept: the stations (errand cells) of the file.
  std::vector<planner::Vertex> errand_cells() const
  {
    std::vector<planner::Vertex> out;
    for (const std::vector<planner::Vertex>& t : tasks) out.insert(out.end(), t.begin(), t.end());
    return out;
  }
};

TaskFile load_lorr_tasks(const std::string& path, const planner::Graph& g);

// Cell id -> vertex, or InputError naming path:line ("off the map", "an obstacle").
planner::Vertex lorr_cell(const planner::Graph& g, long long id, const std::string& path, int line);

}  // namespace tasks
