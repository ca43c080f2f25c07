#pragma once
// Rng: SplitMix64 (Steele, Lea, Flood 2014). PIBT draws several numbers per agent per
// expansion, so the generator must be tiny and fast; determinism across platforms matters
// for the identical-tree property, so no std:: distributions are used.
#include <cstdint>
#include <utility>

namespace planner {

class Rng {
 public:
  explicit Rng(uint64_t seed = 0) : s_(seed) {}
  uint64_t next()
  {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float uniform() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }  // [0, 1)
  uint32_t below(uint32_t n) { return static_cast<uint32_t>(((next() >> 32) * n) >> 32); }

  template <class T>
  void shuffle(T* a, int n)
  {
    for (int k = n - 1; k > 0; --k) std::swap(a[k], a[below(static_cast<uint32_t>(k + 1))]);
  }

 private:
  uint64_t s_;
};

}  // namespace planner
