#include "tasks/hungarian_assigner.hpp"

#include <algorithm>
#include <stdexcept>

#include "tasks/greedy_assigner.hpp"
#include "tasks/hungarian.hpp"

namespace tasks {

std::vector<int> HungarianAssigner::assign(int rows, int cols, const CostFn& cost)
{
  std::vector<int> out(rows, -1);
  std::vector<char> taken(cols, 0);
  for (int b0 = 0; b0 < rows; b0 += max_batch_) {
    const int b1 = std::min(rows, b0 + max_batch_);
    // Candidate columns: each row's k cheapest free tasks (all free tasks when few).
    std::vector<int> free_cols;
    for (int j = 0; j < cols; ++j)
      if (!taken[j]) free_cols.push_back(j);
    if (free_cols.empty()) break;
    std::vector<int> cand;
    if (static_cast<int>(free_cols.size()) <= k_) {
      cand = free_cols;
    } else {
      std::vector<char> in(cols, 0);
      std::vector<std::pair<int64_t, int>> row;
      for (int i = b0; i < b1; ++i) {
        row.clear();
        for (int j : free_cols) row.emplace_back(cost(i, j), j);
        std::nth_element(row.begin(), row.begin() + (k_ - 1), row.end());
        for (int k = 0; k < k_; ++k) in[row[k].second] = 1;
      }
      for (int j : free_cols)
        if (in[j]) cand.push_back(j);
    }
    const int n = b1 - b0, m = static_cast<int>(cand.size());
    std::vector<int64_t> c(static_cast<size_t>(n) * m);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) c[static_cast<size_t>(i) * m + j] = cost(b0 + i, cand[j]);
    const std::vector<int> match = min_cost_assignment(n, m, c);
    for (int i = 0; i < n; ++i)
      if (match[i] >= 0) {
        out[b0 + i] = cand[match[i]];
        taken[cand[match[i]]] = 1;
      }
  }
  return out;
}

std::unique_ptr<TaskAssigner> make_assigner(const std::string& name, int k_nearest)
{
  if (name == "greedy") return std::make_unique<GreedyAssigner>();
  if (name == "hungarian") return std::make_unique<HungarianAssigner>(k_nearest);
  throw std::invalid_argument("unknown assigner '" + name + "' (greedy | hungarian)");
}

}  // namespace tasks
