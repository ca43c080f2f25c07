#pragma once
// Model: the policy network, a multilayer perceptron. Dense layers with ReLU between them
// (none after the last); the last layer has kNumActions outputs, the action logits.
// Forward passes run batched over all agents: one matrix product per layer, so the cost
// of a planning step is a handful of GEMMs rather than N small ones.
//
// Weights follow PyTorch's nn.Linear: w is out x in and a layer computes w * x + b, so a
// trained torch model exports without transposes (scripts/train_policy.py).
#include <vector>

#include <Eigen/Core>

#include "policy/observation.hpp"

namespace policy {

struct Dense {
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> w;  // out x in
  Eigen::VectorXf b;                                                        // out
};

struct Model {
  ObservationSpec spec;        // the observations the network was trained on
  std::vector<Dense> layers;

  int input_size() const { return layers.empty() ? 0 : static_cast<int>(layers.front().w.cols()); }
  int output_size() const { return layers.empty() ? 0 : static_cast<int>(layers.back().w.rows()); }
  size_t num_parameters() const;

  // Logits for a batch: x is input_size() x n (column-major, one column per agent, the
  // layout ObservationBuilder writes); `logits` becomes output_size() x n.
  void forward(const Eigen::Ref<const Eigen::MatrixXf>& x, Eigen::MatrixXf& logits) const;
};

}  // namespace policy
