#pragma once
// GreedyAssigner: free agents in order (row 0 first) each take the cheapest task still
// free; ties go to the lower column (the older task). O(rows x cols) cost lookups.
#include "tasks/assigner.hpp"

namespace tasks {

class GreedyAssigner : public TaskAssigner {
 public:
  std::string name() const override { return "greedy"; }
  std::vector<int> assign(int rows, int cols, const CostFn& cost) override;
};

}  // namespace tasks
