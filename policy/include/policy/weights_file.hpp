#pragma once
// The weights file of a Model: versioned little-endian binary, written by
// scripts/train_policy.py. Version 1:
//
//   char[8]  magic "RTLPOLCY"
//   uint32   version (1)
//   uint32   radius        observation window radius r (window 2r+1), 1..32
//   uint32   channels      must equal kChannels (4)
//   uint32   actions       must equal kNumActions (5)
//   uint32   layers L      1..16
//   L times: uint32 out, uint32 in (1..65536 each), float32 w[out*in] (row-major, out x in),
//            float32 b[out]
//   end of file
//
// Shapes must chain: layer 0 takes channels*(2r+1)^2 inputs, layer k takes layer k-1's
// outputs, the last has `actions` outputs. Every value must be finite. Anything else --
// missing file, wrong magic or version, bad shape, truncation, trailing bytes -- throws
// planner::InputError with one line naming the file and what is wrong.
#include <string>

#include "policy/model.hpp"

namespace policy {

constexpr char kWeightsMagic[8] = {'R', 'T', 'L', 'P', 'O', 'L', 'C', 'Y'};
constexpr uint32_t kWeightsVersion = 1;

Model load_weights(const std::string& path);
// Writes `m` in the format above (tests and tools; training writes it from Python).
void save_weights(const Model& m, const std::string& path);

}  // namespace policy
