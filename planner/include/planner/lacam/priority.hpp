#pragma once
// PIBT's dynamic priorities (Okumura et al., AIJ 2022), as LaCAM uses them per HNode:
// an agent's priority grows by one each step it is away from its goal and drops to its
// fractional part once it arrives; the initial fractional part, dist/N, breaks ties.
// Agents are ordered by descending priority, equal priorities by ascending agent id, so
// the order is a pure function of the priorities.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "planner/dist_table.hpp"
#include "planner/priority_hint.hpp"

namespace planner {

inline void init_priorities(const Vertex* C, int n, DistTable& D, float* prio)
{
  for (int i = 0; i < n; ++i) prio[i] = static_cast<float>(D.get(i, C[i])) / static_cast<float>(n);
}

// Agents [begin, end) only (a resumable expansion computes a node's priorities in pieces).
inline void next_priorities(const Vertex* C, int begin, int end, DistTable& D, const float* parent, float* prio)
{
  for (int i = begin; i < end; ++i)
    prio[i] = D.get(i, C[i]) != 0 ? parent[i] + 1.0f : parent[i] - static_cast<float>(static_cast<int>(parent[i]));
}

inline void next_priorities(const Vertex* C, int n, DistTable& D, const float* parent, float* prio)
{
  next_priorities(C, 0, n, D, parent, prio);
}

// Insertion sort's steps [begin, end): order[begin, end) go into the sorted order[0, begin).
// Steps [1, n) sort it all; a resumable expansion makes them in pieces.
inline void insert_by_priority(const float* prio, int32_t* order, int begin, int end)
{
  auto before = [prio](int32_t a, int32_t b) { return prio[a] > prio[b] || (prio[a] == prio[b] && a < b); };
  for (int k = std::max(begin, 1); k < end; ++k) {
    int32_t a = order[k];
    int j = k;
    for (; j > 0 && before(a, order[j - 1]); --j) order[j] = order[j - 1];
    order[j] = a;
  }
}

// Priority hints (RealtimePlanner::set_priority_hint): the task layer's urgency, a floor
// under an agent's priority at an epoch start: max(priority, tie + round(hint)), `tie` its
// initial priority (dist/N) (planner/priority_hint.hpp); a carried priority above the floor
// stays (keep_priorities). Unlike PIBT's elapsed time, the hint survives goal changes:
// an errand stalled for 300 ticks beats one opened 5 ticks ago in every epoch.
inline void raise_to_hint(const float* tie, const std::vector<float>& hint, int n, float* prio)
{
  if (static_cast<int>(hint.size()) != n) return;
  for (int i = 0; i < n; ++i) prio[i] = hint_floor(prio[i], tie[i], hint[i]);
}

// Sorts `order` (a permutation of 0..n-1) by descending priority. Insertion sort: the
// caller passes the parent's order, which is nearly sorted already, so this is ~O(n).
inline void sort_by_priority(const float* prio, int n, int32_t* order) { insert_by_priority(prio, order, 1, n); }

inline void initial_order(const float* prio, int n, int32_t* order)
{
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order, order + n, [prio](int32_t a, int32_t b) { return prio[a] > prio[b] || (prio[a] == prio[b] && a < b); });
}

}  // namespace planner
