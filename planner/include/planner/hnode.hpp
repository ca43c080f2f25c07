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

struct HNode {
  const Vertex* C = nullptr;         // configuration, N entries
  const int32_t* order = nullptr;    // agents by descending priority
  const float* priorities = nullptr; // PIBT priorities at this configuration
  HNode* parent = nullptr;           // search-tree edge (reversed by RT-LaCAM's reroot)
  Constraint* head = nullptr;        // low-level queue
  Constraint* tail = nullptr;
  uint64_t hash = 0;
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
