#pragma once
// Blocked vertices: cells nobody may enter for a while (an aisle closed at run time, a
// one-at-a-time zone someone else is in). The planner needs no new mechanism for them: a
// planner built on blocked_graph() below cannot plan a move into a blocked vertex, because
// the graph has no such arc. Every vertex keeps its id, so configurations, plans and the
// validator on the full graph stay valid.
//
// An agent standing on a blocked vertex when the block begins must be able to leave: arcs
// OUT of a blocked region stay, and inside the region an agent may move only to a vertex
// strictly nearer (along arcs) to an unblocked one -- an evacuation order without cycles,
// so nobody can circle inside. The result is a directed graph (the LaCAM family plans on
// it; lacam/rt_lacam.hpp states the guarantee: complete when the goal configuration is
// reachable). A goal on a blocked vertex is unreachable in it: the caller decides what the
// agent does instead (controller/rules.hpp: it waits).
#include <cstdint>
#include <functional>
#include <vector>

#include "planner/graph.hpp"

namespace planner {

// `g` without the arcs `drop(u, v)` names; vertices, positions and the grid view are kept.
Graph without_arcs(const Graph& g, const std::function<bool(Vertex, Vertex)>& drop);

// Steps from each vertex to the nearest vertex with blocked[v] == 0 along arcs of `g`
// (0 on unblocked vertices; -1 where no unblocked vertex can be reached).
std::vector<int32_t> exit_distance(const Graph& g, const std::vector<uint8_t>& blocked);

// `g` without the arcs into blocked vertices, except the evacuation arcs u -> v inside a
// blocked region with exit_distance(v) < exit_distance(u). blocked: one entry per vertex.
Graph blocked_graph(const Graph& g, const std::vector<uint8_t>& blocked);

}  // namespace planner
