#include "policy/golden_file.hpp"

#include "policy/binary_reader.hpp"

namespace policy {

Golden load_golden(const std::string& path)
{
  BinaryReader in(path);
  in.expect_magic(kGoldenMagic, "policy golden file");
  const uint32_t version = in.u32("version");
  if (version != kGoldenVersion) throw in.error("unsupported golden file version " + std::to_string(version));
  const uint32_t n = in.u32("sample count"), inputs = in.u32("input size"), outputs = in.u32("output size");
  if (n < 1 || n > 1000000 || inputs < 1 || inputs > 65536 || outputs < 1 || outputs > 65536)
    throw in.error("implausible shape " + std::to_string(n) + " x " + std::to_string(inputs) + " -> " + std::to_string(outputs));
  // The shape allows 1e6 x 65536 floats (262 GB): check the file holds each matrix
  // before allocating it, so a corrupt header is "truncated", not std::bad_alloc.
  const uint64_t x_bytes = static_cast<uint64_t>(inputs) * n * sizeof(float);
  const uint64_t logit_bytes = static_cast<uint64_t>(outputs) * n * sizeof(float);
  Golden g;
  in.need(x_bytes, "inputs");
  g.x.resize(inputs, n);
  in.read(g.x.data(), x_bytes, "inputs");
  in.need(logit_bytes, "logits");
  g.logits.resize(outputs, n);
  in.read(g.logits.data(), logit_bytes, "logits");
  in.expect_end();
  return g;
}

}  // namespace policy
