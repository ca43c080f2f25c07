#pragma once
// HungarianAssigner: min-cost matching of free agents to free tasks.
//
// With thousands of agents the full matrix is too big, so each agent keeps only its
// k_nearest cheapest tasks as candidates; the matrix is rows x (union of candidates), and
// agents are matched in batches of at most max_batch rows (earlier batches' tasks are gone
// for later ones). When every agent's candidates are all tasks (rows * k >= cols and one
// batch), this is the exact optimum.
#include "tasks/assigner.hpp"

namespace tasks {

class HungarianAssigner : public TaskAssigner {
 public:
  explicit HungarianAssigner(int k_nearest = 32, int max_batch = 512) : k_(k_nearest), max_batch_(max_batch) {}
  std::string name() const override { return "hungarian"; }
  std::vector<int> assign(int rows, int cols, const CostFn& cost) override;

 private:
  int k_, max_batch_;
};

}  // namespace tasks
