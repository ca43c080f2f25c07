#pragma once
// Guidance: a guidance graph for the rotation action model (LoRR MAPF_T): a cost per
// forward move, per (cell, heading), and one cost per quarter turn. RotationDist's tables
// become distances in these costs, so PIBT ranks moves by them: robots prefer the cheap
// direction of each lane and flows in opposite directions separate, which is what the LoRR
// entrants' guidance does (WPPL ranks PIBT on an optimised guidance graph, Jiang et al.
// 2024 / Zhang et al. IJCAI 2024; "No Man's Sky", LoRR 2024, an arrow field with forward
// costs 2 along / 6 against and turns 2). Costs never forbid a move: every state that can
// reach a goal without guidance still can, the guidance only reorders PIBT's candidates.
//
// Sources:
//  - arrow_guidance(): a one-way-lane field that needs no offline optimisation. Rows
//    alternate east / west, columns alternate south / north: a forward move along its
//    lane's arrow costs `along`, against it `against`. Rows (columns) are numbered among
//    those that hold a move along them, from the first one's parity, so aisles several
//    cells apart alternate too (a gridified warehouse with an aisle every 4th column); on
//    a map whose every row and column holds a move this is even y east, even x south. Then the
//    cheap arcs (cells joined by an `along` move) are repaired until they are strongly
//    connected per connected component of the map: while they are not, every costly arc
//    between two of their strongly connected components becomes cheap. Dead ends and
//    one-cell pockets so get a cheap way in and out, and a robot can reach every cell on
//    cheap moves (costly ones stay usable).
//  - load_guidance(): a text file, so optimised weights (e.g. GGO's) can be plugged in:
//        # comment; blank lines ignored
//        turn T              cost of a quarter turn (optional, default 1)
//        default C           forward cost of every arc not listed (optional, default 1)
//        X Y CE CS CW CN     forward costs from cell (X, Y) facing east, south, west, north
//    Costs are integers 1..kMaxCost; a cell line names a free cell of the map, once.
//    Errors throw InputError "file:line: what". save_guidance() writes this format.
//
// Why small integers: RotationDist's search is Dijkstra on a bucket (Dial) queue with one
// bucket per cost value, and its distances are uint16 (kMaxCost * the longest path must
// stay below 65,534: 1,000-step paths at cost 60).
#include <cstdint>
#include <string>
#include <vector>

#include "planner/graph.hpp"

namespace planner {

struct Guidance {
  static constexpr int kMaxCost = 60;
  std::vector<uint16_t> forward;  // v * 4 + o -> cost of moving forward from v facing o; empty: all 1
  uint16_t turn = 1;              // a quarter turn (either way)

  // No guidance: every action costs 1 (RotationDist then runs its plain BFS).
  bool uniform() const;
  uint16_t forward_cost(Vertex v, int o) const { return forward.empty() ? 1 : forward[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)]; }
  uint16_t min_forward() const;  // over every arc (1 when uniform)
  uint16_t max_cost() const;     // over forward arcs and the turn
};

// The one-way-lane field above; along, against, turn in 1..kMaxCost (std::invalid_argument
// otherwise). Needs a grid graph.
Guidance arrow_guidance(const Graph& g, int along, int against, int turn);

// Whether the arcs of cost <= `cheap` join every pair of cells that the map joins (each
// connected component strongly connected on them).
bool cheap_arcs_strongly_connected(const Graph& g, const Guidance& gd, uint16_t cheap);

Guidance load_guidance(const Graph& g, const std::string& path);
// `header`: lines written first as '# ' comments (how the weights were made).
void save_guidance(const Graph& g, const Guidance& gd, const std::string& path, const std::string& header = "");

}  // namespace planner
