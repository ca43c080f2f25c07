#pragma once
// Dump file: (observation, expert action) pairs for imitation learning, written by
// `rtlacam-policy dump` and read by scripts/train_policy.py (numpy). Every observation
// value is a multiple of 1/scale[channel] (observation.hpp), so it is stored exactly as
// an int8: 4x smaller than float32, which keeps a few hundred thousand samples in memory.
// Little-endian binary, version 1:
//
//   char[8] magic "RTLPDUMP", uint32 version (1), uint32 radius, uint32 channels,
//   uint32 features (= channels * (2r+1)^2), float32 scale[channels], uint64 count,
//   count records of (features + 2) bytes:
//     int8 q[features]   observation: x = q / scale[channel of the feature]
//     uint8 action       the expert's next action (actions.hpp)
//     uint8 flags        bit 0: the agent is on its goal; bit 1: some agent of this step
//                        has not arrived yet (the instance is still being solved)
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "policy/observation.hpp"

namespace policy {

constexpr char kDumpMagic[8] = {'R', 'T', 'L', 'P', 'D', 'U', 'M', 'P'};
constexpr uint32_t kDumpVersion = 1;

class DumpWriter {
 public:
  DumpWriter(const std::string& path, ObservationSpec spec);  // throws InputError if unwritable
  ~DumpWriter();

  void add(const float* obs, int action, uint8_t flags);
  void close();  // writes the record count; also done by the destructor
  uint64_t count() const { return count_; }

 private:
  std::string path_;
  ObservationSpec spec_;
  std::ofstream out_;
  std::vector<float> scale_;       // per feature
  std::vector<int8_t> record_;
  std::streampos count_pos_;
  uint64_t count_ = 0;
  bool closed_ = false;
};

}  // namespace policy
