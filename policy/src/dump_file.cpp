#include "policy/dump_file.hpp"

#include <cmath>
#include <stdexcept>

#include "planner/error.hpp"

namespace policy {

DumpWriter::DumpWriter(const std::string& path, ObservationSpec spec)
    : path_(path), spec_(spec), out_(path, std::ios::binary), record_(static_cast<size_t>(spec.size()) + 2)
{
  if (!out_) throw planner::input_error(path, 0, "cannot write file");
  float channel_scale[kChannels];
  for (int c = 0; c < kChannels; ++c) channel_scale[c] = c == kGoalDistance ? static_cast<float>(2 * spec.radius) : 1.0f;
  const int area = spec.window() * spec.window();
  for (int f = 0; f < spec.size(); ++f) scale_.push_back(channel_scale[f / area]);

  auto u32 = [&](uint32_t v) { out_.write(reinterpret_cast<const char*>(&v), sizeof v); };
  out_.write(kDumpMagic, 8);
  u32(kDumpVersion);
  u32(static_cast<uint32_t>(spec.radius));
  u32(kChannels);
  u32(static_cast<uint32_t>(spec.size()));
  out_.write(reinterpret_cast<const char*>(channel_scale), sizeof channel_scale);
  count_pos_ = out_.tellp();
  const uint64_t zero = 0;
  out_.write(reinterpret_cast<const char*>(&zero), sizeof zero);
}

DumpWriter::~DumpWriter()
{
  try {
    close();
  } catch (...) {
  }
}

void DumpWriter::add(const float* obs, int action, uint8_t flags)
{
  for (int f = 0; f < spec_.size(); ++f) {
    const float q = std::round(obs[f] * scale_[f]);
    if (q / scale_[f] != obs[f] || q < -127 || q > 127)
      throw std::logic_error("dump: observation value " + std::to_string(obs[f]) + " does not quantise exactly");
    record_[f] = static_cast<int8_t>(q);
  }
  record_[spec_.size()] = static_cast<int8_t>(action);
  record_[spec_.size() + 1] = static_cast<int8_t>(flags);
  out_.write(reinterpret_cast<const char*>(record_.data()), static_cast<std::streamsize>(record_.size()));
  ++count_;
}

void DumpWriter::close()
{
  if (closed_) return;
  closed_ = true;
  out_.seekp(count_pos_);
  out_.write(reinterpret_cast<const char*>(&count_), sizeof count_);
  out_.close();
  if (!out_) throw planner::input_error(path_, 0, "write failed");
}

}  // namespace policy
