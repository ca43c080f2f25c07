#include "tasks/greedy_assigner.hpp"

#include <limits>

namespace tasks {

std::vector<int> GreedyAssigner::assign(int rows, int cols, const CostFn& cost)
{
  std::vector<int> out(rows, -1);
  std::vector<char> taken(cols, 0);
  for (int i = 0; i < rows; ++i) {
    int64_t best = std::numeric_limits<int64_t>::max();
    for (int j = 0; j < cols; ++j) {
      if (taken[j]) continue;
      const int64_t c = cost(i, j);
      if (c < best && c < kForbidden) best = c, out[i] = j;
    }
    if (out[i] >= 0) taken[out[i]] = 1;
  }
  return out;
}

}  // namespace tasks
