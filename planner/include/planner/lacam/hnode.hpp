#pragma once
// The two node kinds of LaCAM (Okumura, AAAI-23).
//
// HNode: a high-level node, one per explored configuration. It owns a lazily grown
// low-level tree of Constraints, kept as a FIFO queue (breadth-first over the tree, as in
// the paper): the k-th time the node is revisited, the next constraint in the queue fixes
// the first agents (in priority order) to specific vertices before PIBT fills in the rest.
//
// Constraint: a low-level node. It fixes agent `who` to vertex `where` and inherits the
// fixes of its parent chain; `depth` is the number of fixed agents. Chaining (instead of
// copying the who/where lists as the reference code does) makes creation O(1).
//
// Neighbor: one link of LaCAM*'s neighbour sets (Okumura, IJCAI-23): a configuration the
// node was seen to connect to (a successor it generated, or a node that generated it).
// Links are kept in both directions where both are legal -- on an undirected graph a valid
// transition reversed is valid, and the paper's edge cost is symmetric -- so that a reroot
// can walk the tree both ways. On a directed graph the reverse link is left out when the
// transition used a one-way arc (Lacam::link). `cost`
// is computed lazily (-1 = not yet): recording links before the first solution then costs
// a pointer push, not an O(N) comparison.
#include <cstdint>

#include "planner/graph.hpp"

namespace planner {

struct Constraint {
  const Constraint* parent = nullptr;  // shallower constraint, nullptr for the empty one
  Constraint* next = nullptr;          // FIFO link inside the owner's queue
  int32_t who = -1;                    // agent fixed by this node (-1 at depth 0)
  Vertex where = -1;                   // its vertex in the successor configuration
  int32_t depth = 0;
};

struct HNode;

struct Neighbor {
  HNode* to = nullptr;
  Neighbor* next = nullptr;
  int32_t cost = -1;
};

struct HNode {
  const Vertex* C = nullptr;         // configuration, N entries
  const int32_t* order = nullptr;    // agents by descending priority
  const float* priorities = nullptr; // PIBT priorities at this configuration
  HNode* parent = nullptr;           // search-tree edge (reversed by RT-LaCAM's reroot)
  Constraint* head = nullptr;        // low-level queue
  Constraint* tail = nullptr;
  Neighbor* neighbors = nullptr;      // LaCAM* neighbour set (LacamOptions::refine only)
  uint64_t hash = 0;
  int64_t g = 0;                     // LaCAM*: cost of the tree path from the current root
  int32_t h = 0;                     // LaCAM*: sum of distances to the goals (admissible)
  uint32_t id = 0;                   // creation index (0 = first root)

  void push(Constraint* c)
  {
    c->next = nullptr;
    if (tail) tail->next = c; else head = c;
    tail = c;
  }
  Constraint* pop()
  {
    Constraint* c = head;
    if (c) {
      head = c->next;
      if (!head) tail = nullptr;
    }
    return c;
  }
};

}  // namespace planner
