#pragma once
// Writes an executed plan in the result format of Kei18's LaCAM/PIBT tools, which their
// visualisers read: key=value header lines, then "solution=" and one line per timestep
// "t:(x,y),(x,y),..." with x = column, y = row on grid maps (display position otherwise,
// or the vertex id as (v,0) when the graph has no positions).
#include <istream>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace planner {

struct PlanHeader {
  std::string map_file, solver;
  bool solved = false;
  long long soc = 0, soc_lb = 0, makespan = 0;
  double comp_time_ms = 0;
  std::vector<std::pair<std::string, std::string>> extra;  // more key=value lines
};

void write_plan(std::ostream& out, const Graph& g, const Config& starts, const Config& goals,
                const std::vector<Config>& plan, const PlanHeader& h);
// The same in pieces, for a plan written as it grows: the header up to "solution=", then
// the lines "t:..." of plan[0..] numbered from `first_t`.
void write_plan_header(std::ostream& out, const Graph& g, const Config& starts, const Config& goals,
                       const PlanHeader& h);
void write_plan_steps(std::ostream& out, const Graph& g, const std::vector<Config>& plan, size_t first_t);

// The "solution=" section of a result file in that format (ours, lacam's, lacam3's) on a
// grid graph: C^0 .. C^T. Throws InputError (one line: file, line, what) on a malformed
// line or a cell off the map; `source` names the file in messages.
std::vector<Config> read_plan(std::istream& in, const Graph& g, const std::string& source);

}  // namespace planner
