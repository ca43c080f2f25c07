#pragma once
// Golden file: inputs and the PyTorch model's outputs on them, written next to the weights
// by scripts/train_policy.py, so that a test without torch can check that the Eigen forward
// pass computes what was trained. Little-endian binary, version 1:
//
//   char[8] magic "RTLGOLDN", uint32 version (1), uint32 n, uint32 inputs, uint32 outputs,
//   float32 x[n * inputs]       sample after sample (= an inputs x n column-major matrix)
//   float32 logits[n * outputs] sample after sample
//
// Errors throw planner::InputError naming the file.
#include <string>

#include <Eigen/Core>

namespace policy {

constexpr char kGoldenMagic[8] = {'R', 'T', 'L', 'G', 'O', 'L', 'D', 'N'};
constexpr uint32_t kGoldenVersion = 1;

struct Golden {
  Eigen::MatrixXf x;       // inputs x n
  Eigen::MatrixXf logits;  // outputs x n
};

Golden load_golden(const std::string& path);

}  // namespace policy
