#pragma once
// Config: a joint configuration, the vertex of every agent (index = agent id).
// The search stores configurations in arenas and passes them around as raw pointers of
// length N; `Config` is the owning form used at the API boundary.
#include <cstdint>
#include <cstring>
#include <vector>

#include "planner/graph.hpp"

namespace planner {

using Config = std::vector<Vertex>;

// FxHash-style mixing per agent plus a SplitMix64 finaliser: fast, and good enough that
// configurations differing in one agent land in different buckets.
inline uint64_t config_hash(const Vertex* c, int n)
{
  uint64_t h = 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(n);
  for (int i = 0; i < n; ++i) {
    h = (h << 5 | h >> 59) ^ static_cast<uint32_t>(c[i]);
    h *= 0x517CC1B727220A95ull;
  }
  h ^= h >> 30;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 27;
  h *= 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

inline bool config_equal(const Vertex* a, const Vertex* b, int n)
{
  return std::memcmp(a, b, sizeof(Vertex) * static_cast<size_t>(n)) == 0;
}

}  // namespace planner
