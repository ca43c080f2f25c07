#pragma once
// Highways: soft one-way guidance in the 1-wide corridors of a grid (after Cohen, Uras,
// Koenig, "Feasibility study: using highways for bounded-suboptimal MAPF", SoCS 2015, and the
// guidance graphs of lifelong MAPF). PIBT sends every agent down its own shortest path, so in
// a warehouse the agents of one long aisle meet head-on and must back out one by one (PIBT's
// swaps); that is where LaCAM's first solution loses most of its cost there. Ranking PIBT's
// moves by distances in which a move against a corridor's grain costs `penalty` more spreads
// the flows over neighbouring aisles in opposite directions, and no extra work is done per
// step: only the distance tables PIBT ranks by are weighted (LacamOptions::highways).
//
// A corridor run is a maximal horizontal (vertical) sequence of free cells each of which has
// obstacles or the map's edge directly above and below (left and right): a 1-wide aisle. Runs
// of at least `min_run` cells get a grain; the rows (columns) holding such runs are numbered
// in order, and the grain alternates with that number (even: east / south, odd: west /
// north), whatever the spacing of the aisles. A move between two cells of one run against its
// grain costs 1 + penalty, if its reverse is a move too (on a directed graph a one-way arc is
// the only way through: nothing to steer); every other move costs 1. Distances stay exact shortest paths
// under these costs, so every vertex keeps its way to every goal (the graph is unchanged).
#include <cstdint>
#include <vector>

#include "planner/graph.hpp"

namespace planner {

struct HighwayOptions {
  int penalty = 1;  // extra cost of a move against a corridor's grain (0: off)
  int min_run = 3;  // least corridor run that gets a grain, cells
};

// Per in-arc extra costs for DistCache::set_arc_costs (num_arcs() entries; arc k into u is
// at Graph::in_arc(u) + k). Empty when
// the graph is not a grid, the penalty is 0, or no run qualifies.
std::vector<uint8_t> highway_costs(const Graph& g, const HighwayOptions& opt);

}  // namespace planner
