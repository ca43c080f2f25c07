#include "tasks/hungarian.hpp"

#include <limits>
#include <stdexcept>

namespace tasks {
namespace {

// n <= m; a(i, j) with 1-based i, j. Classic potentials formulation: rows are added one at
// a time and matched along a shortest augmenting path in reduced costs (Dijkstra-like
// scan over columns), which keeps u[i] + v[j] <= a(i, j) with equality on matched pairs.
template <class A>
std::vector<int> solve(int n, int m, A a)
{
  const int64_t inf = std::numeric_limits<int64_t>::max() / 4;
  std::vector<int64_t> u(n + 1, 0), v(m + 1, 0), minv(m + 1);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  std::vector<char> used(m + 1);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::fill(minv.begin(), minv.end(), inf);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      int64_t delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const int64_t cur = a(i0, j) - u[i0] - v[j];
        if (cur < minv[j]) minv[j] = cur, way[j] = j0;
        if (minv[j] < delta) delta = minv[j], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0);
  }
  std::vector<int> row_to_col(n, -1);
  for (int j = 1; j <= m; ++j)
    if (p[j]) row_to_col[p[j] - 1] = j - 1;
  return row_to_col;
}

}  // namespace

std::vector<int> min_cost_assignment(int rows, int cols, const std::vector<int64_t>& cost)
{
  if (rows < 0 || cols < 0 || cost.size() != static_cast<size_t>(rows) * static_cast<size_t>(cols))
    throw std::invalid_argument("min_cost_assignment: cost matrix has the wrong size");
  if (rows == 0 || cols == 0) return std::vector<int>(rows, -1);
  if (rows <= cols)
    return solve(rows, cols, [&](int i, int j) { return cost[static_cast<size_t>(i - 1) * cols + (j - 1)]; });
  // More rows than columns: match columns to rows on the transpose.
  const std::vector<int> col_to_row =
      solve(cols, rows, [&](int i, int j) { return cost[static_cast<size_t>(j - 1) * cols + (i - 1)]; });
  std::vector<int> out(rows, -1);
  for (int c = 0; c < cols; ++c)
    if (col_to_row[c] >= 0) out[col_to_row[c]] = c;
  return out;
}

}  // namespace tasks
