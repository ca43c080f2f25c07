#pragma once
// Zones: one-at-a-time zones (controller/rules.hpp, issue 24) as a rule of the configurations
// themselves. A zone is a set of vertices. A step C -> C' keeps the zones when, per zone, at
// most one agent is in it at C or at C' together: an agent that leaves a zone holds it for the
// whole step (in SUMO it is still inside while it drives out), and one that enters needs it
// empty at C and nobody else entering.
//
// Why in the planner: a controller that only holds the second entrant back at execution time
// must restart the search at what it executed, and a fresh search per hold keeps no memory of
// the configurations it tried: on a small warehouse with one zone, a lock-step run went 1500
// ticks without reaching its goals (docs/closed_loop_bench.md). With the zones a rule of PIBT
// (pibt.hpp: a move into a zone someone else holds is no candidate; a LaCAM constraint that
// breaks them fails the generation), LaCAM's low-level search enumerates exactly the steps
// that keep them, so LaCAM, RT-LaCAM (a reversed step keeps them too: the rule is symmetric in
// C and C') and LaCAM*'s rewiring stay complete over the configurations that keep them,
// provided the start and the goal configuration have at most one agent per zone. LNS and the
// refiner threads replan paths without PIBT, so they are off while zones are set.
#include <memory>
#include <string>
#include <vector>

#include "planner/config.hpp"

namespace planner {

struct Zones {
  std::vector<std::vector<int>> of;        // vertex -> the zones it is in (empty: none)
  std::vector<std::vector<Vertex>> cells;  // zone -> its vertices
  int count = 0;

  // Zones from their cells (zone z = cells[z]) on a graph of `num_vertices` vertices.
  static std::shared_ptr<const Zones> from_cells(size_t num_vertices, const std::vector<std::vector<Vertex>>& cells);
  bool in(Vertex v, int z) const;
};

// The first zone the step from -> to breaks, as "zone Z: agents I and J" ("" if none).
std::string zone_conflict(const Zones& zones, const Config& from, const Config& to);

}  // namespace planner
