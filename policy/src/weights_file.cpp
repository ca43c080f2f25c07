#include "policy/weights_file.hpp"

#include <cmath>
#include <fstream>

#include "policy/actions.hpp"
#include "policy/binary_reader.hpp"
#include "planner/output_file.hpp"

namespace policy {
namespace {

constexpr uint32_t kMaxRadius = 32, kMaxLayers = 16, kMaxWidth = 65536;

void read_floats(BinaryReader& in, float* dst, uint64_t count, const std::string& what)
{
  in.read(dst, count * sizeof(float), what);
  for (uint64_t k = 0; k < count; ++k)
    if (!std::isfinite(dst[k])) throw in.error(what + " has a non-finite value at index " + std::to_string(k));
}

}  // namespace

Model load_weights(const std::string& path)
{
  BinaryReader in(path);
  in.expect_magic(kWeightsMagic, "policy weights file");
  const uint32_t version = in.u32("version");
  if (version != kWeightsVersion)
    throw in.error("unsupported weights version " + std::to_string(version) + " (this build reads version " +
                   std::to_string(kWeightsVersion) + ")");
  const uint32_t radius = in.u32("radius"), channels = in.u32("channels"), actions = in.u32("actions");
  const uint32_t num_layers = in.u32("layer count");
  if (radius < 1 || radius > kMaxRadius) throw in.error("radius " + std::to_string(radius) + " not in 1..32");
  if (channels != kChannels)
    throw in.error("model has " + std::to_string(channels) + " observation channels, this build has " + std::to_string(kChannels));
  if (actions != kNumActions)
    throw in.error("model has " + std::to_string(actions) + " actions, expected " + std::to_string(kNumActions));
  if (num_layers < 1 || num_layers > kMaxLayers) throw in.error("layer count " + std::to_string(num_layers) + " not in 1..16");

  Model m;
  m.spec.radius = static_cast<int>(radius);
  uint32_t expected_in = static_cast<uint32_t>(m.spec.size());
  for (uint32_t k = 0; k < num_layers; ++k) {
    const std::string name = "layer " + std::to_string(k);
    const uint32_t out = in.u32(name + " output size"), inputs = in.u32(name + " input size");
    if (out < 1 || out > kMaxWidth || inputs < 1 || inputs > kMaxWidth)
      throw in.error(name + " shape " + std::to_string(out) + "x" + std::to_string(inputs) + " out of range 1..65536");
    if (inputs != expected_in)
      throw in.error(name + " takes " + std::to_string(inputs) + " inputs, expected " + std::to_string(expected_in) +
                     (k == 0 ? " (4 channels x " + std::to_string(m.spec.window()) + "^2 window)" : " (previous layer's outputs)"));
    if (k + 1 == num_layers && out != kNumActions)
      throw in.error("last layer has " + std::to_string(out) + " outputs, expected " + std::to_string(kNumActions) + " action logits");
    // Up to 65536 x 65536 floats (16 GiB): check the file holds them before allocating.
    const uint64_t count = static_cast<uint64_t>(out) * inputs;
    in.need(count * sizeof(float), name + " weights");
    Dense d;
    d.w.resize(out, inputs);
    d.b.resize(out);
    read_floats(in, d.w.data(), count, name + " weights");
    read_floats(in, d.b.data(), out, name + " bias");
    m.layers.push_back(std::move(d));
    expected_in = out;
  }
  in.expect_end();
  return m;
}

void save_weights(const Model& m, const std::string& path)
{
  planner::write_file(path, [&](std::ostream& out) {
    auto u32 = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), sizeof v); };
    out.write(kWeightsMagic, 8);
    u32(kWeightsVersion);
    u32(static_cast<uint32_t>(m.spec.radius));
    u32(kChannels);
    u32(kNumActions);
    u32(static_cast<uint32_t>(m.layers.size()));
    for (const Dense& d : m.layers) {
      u32(static_cast<uint32_t>(d.w.rows()));
      u32(static_cast<uint32_t>(d.w.cols()));
      out.write(reinterpret_cast<const char*>(d.w.data()), static_cast<std::streamsize>(d.w.size() * sizeof(float)));
      out.write(reinterpret_cast<const char*>(d.b.data()), static_cast<std::streamsize>(d.b.size() * sizeof(float)));
    }
  });
}

}  // namespace policy
