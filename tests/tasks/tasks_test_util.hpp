#pragma once
// Helpers for the task-layer tests: tiny grids from strings, temporary files, task files
// built from cells.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "planner/graph.hpp"
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

// A file under the test's temporary directory with the given text.
inline std::string temp_file(const std::string& name, const std::string& text)
{
  return test::temp_file(name, text);
}

}  // namespace ttest
