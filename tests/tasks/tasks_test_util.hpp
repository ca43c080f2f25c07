#pragma once
// Helpers for the task-layer tests: tiny grids from strings, temporary files, task files
// built from cells, bundled LoRR problems.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "planner/graph.hpp"
#include "planner/movingai.hpp"
#include "tasks/lorr_problem.hpp"
#include "tasks/lorr_files.hpp"
#include "grid.hpp"
#include "temp_path.hpp"

namespace ttest {

inline const std::string kData = RTLACAM_TEST_DATA "/tasks/lorr";

using test::grid;  // '.' free, anything else blocked

inline planner::Vertex at(const planner::Graph& g, int x, int y) { return g.at(x, y); }

// Task file from lists of (x, y) cells.
inline std::shared_ptr<const tasks::TaskFile> task_file(const planner::Graph& g,
                                                        const std::vector<std::vector<std::pair<int, int>>>& lines)
{
  auto f = std::make_shared<tasks::TaskFile>();
  f->path = "<test>";
  int n = 0;
  for (const auto& l : lines) {
    std::vector<planner::Vertex> e;
    for (auto [x, y] : l) e.push_back(g.at(x, y));
    f->tasks.push_back(e);
    f->lines.push_back(++n);
  }
  return f;
}

// A LoRR problem under tests/data/tasks/lorr (`rel` starts with '/') with its map, agents
// and task file loaded.
struct Lorr {
  tasks::LorrProblem p;
  planner::Graph g;
  planner::Config starts;
  std::shared_ptr<const tasks::TaskFile> file;
  explicit Lorr(const std::string& rel)
      : p(tasks::load_lorr_problem(kData + rel)), g(planner::load_map(p.map_file)),
        starts(tasks::load_lorr_agents(p.agent_file, g, p.team_size)),
        file(std::make_shared<const tasks::TaskFile>(tasks::load_lorr_tasks(p.task_file, g)))
  {
  }
};

// A file under the test's temporary directory with the given text.
inline std::string temp_file(const std::string& name, const std::string& text)
{
  return test::temp_file(name, text);
}

// Replays one MAPF_T letter from (cell v, heading h): the cell after the step (h turns in place).
inline planner::Vertex apply(const planner::Graph& g, planner::Vertex v, int& h, char a)
{
  static const int dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
  if (a == 'R') h = (h + 1) % 4;
  else if (a == 'C') h = (h + 3) % 4;
  else if (a == 'F') v = g.at(g.cell_x(v) + dx[h], g.cell_y(v) + dy[h]);
  return v;
}

}  // namespace ttest
