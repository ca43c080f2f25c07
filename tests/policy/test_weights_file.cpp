// Weights file: round trip, and every malformed file is one clear InputError naming it.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "planner/error.hpp"
#include "policy/actions.hpp"
#include "policy/weights_file.hpp"
#include "address_cap.hpp"
#include "temp_path.hpp"

using namespace policy;

namespace {

std::string temp_path(const std::string& name)
{
  return test::temp_path("policy_" + name);
}

Model tiny_model()
{
  Model m;
  m.spec.radius = 1;  // 4 x 3 x 3 = 36 inputs
  Dense a, b;
  a.w.resize(3, 36);
  a.b.resize(3);
  b.w.resize(kNumActions, 3);
  b.b.resize(kNumActions);
  for (int k = 0; k < a.w.size(); ++k) a.w.data()[k] = 0.01f * static_cast<float>(k % 17) - 0.05f;
  a.b << 0.1f, -0.2f, 0.3f;
  for (int k = 0; k < b.w.size(); ++k) b.w.data()[k] = 0.1f * static_cast<float>(k) - 0.7f;
  b.b << 1, 2, 3, 4, 5;
  m.layers = {a, b};
  return m;
}

std::vector<char> bytes_of(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<char>& b)
{
  std::ofstream out(path, std::ios::binary);
  out.write(b.data(), static_cast<std::streamsize>(b.size()));
}

// Loads `path`, expecting an InputError whose one-line message names the file and says `what`.
void expect_error(const std::string& path, const std::string& what)
{
  try {
    load_weights(path);
    ADD_FAILURE() << "no error for " << path << " (expected '" << what << "')";
  } catch (const planner::InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

void put_u32(std::vector<char>& b, size_t offset, uint32_t v)
{
  std::memcpy(b.data() + offset, &v, sizeof v);
}

}  // namespace

TEST(WeightsFile, RoundTrip)
{
  const std::string p = temp_path("roundtrip.bin");
  const Model m = tiny_model();
  save_weights(m, p);
  const Model r = load_weights(p);
  EXPECT_EQ(r.spec.radius, 1);
  ASSERT_EQ(r.layers.size(), 2u);
  EXPECT_EQ(r.layers[0].w, m.layers[0].w);
  EXPECT_EQ(r.layers[1].b, m.layers[1].b);
  EXPECT_EQ(r.input_size(), 36);
  EXPECT_EQ(r.output_size(), kNumActions);
  EXPECT_EQ(r.num_parameters(), 36u * 3 + 3 + 3 * 5 + 5);
  // header (8 + 5*4) + per layer (8 + floats)
  EXPECT_EQ(bytes_of(p).size(), 28u + 8 + 4 * (108 + 3) + 8 + 4 * (15 + 5));
}

TEST(WeightsFile, MissingFile)
{
  expect_error(temp_path("does_not_exist.bin"), "cannot open file");
}

TEST(WeightsFile, EveryTruncationIsReported)
{
  const std::string good = temp_path("good.bin"), cut = temp_path("cut.bin");
  save_weights(tiny_model(), good);
  const std::vector<char> b = bytes_of(good);
  for (size_t len = 0; len < b.size(); ++len) {
    SCOPED_TRACE(len);
    write_bytes(cut, std::vector<char>(b.begin(), b.begin() + static_cast<long>(len)));
    expect_error(cut, len < 8 ? "file too short" : "truncated file");
  }
}

TEST(WeightsFile, BadHeaders)
{
  const std::string good = temp_path("good2.bin"), bad = temp_path("bad.bin");
  save_weights(tiny_model(), good);
  const std::vector<char> b = bytes_of(good);

  auto with = [&](size_t offset, uint32_t v) {
    std::vector<char> c = b;
    put_u32(c, offset, v);
    write_bytes(bad, c);
  };
  std::vector<char> c = b;
  c[0] = 'X';
  write_bytes(bad, c);
  expect_error(bad, "bad magic");
  with(8, 2);
  expect_error(bad, "unsupported weights version 2");
  with(12, 0);
  expect_error(bad, "radius 0");
  with(16, 3);
  expect_error(bad, "3 observation channels");
  with(20, 4);
  expect_error(bad, "4 actions");
  with(24, 0);
  expect_error(bad, "layer count 0");
  // The radius says 2 (100 inputs) but layer 0 takes 36.
  with(12, 2);
  expect_error(bad, "layer 0 takes 36 inputs, expected 100");
  // Layer 1 claims 4 inputs: does not chain with layer 0's 3 outputs.
  const size_t layer1 = 28 + 8 + 4 * (108 + 3);
  with(layer1 + 4, 4);
  expect_error(bad, "layer 1 takes 4 inputs, expected 3");
  // Last layer with 6 outputs.
  with(layer1, 6);
  expect_error(bad, "last layer has 6 outputs");
  // A huge claimed shape is rejected before any allocation.
  with(28, 1u << 30);
  expect_error(bad, "out of range");
}

// A 36-byte file whose layer 0 claims 65536 x 16900 weights (radius 32: 4.4 GB) is a
// truncated file, found before the matrix is allocated. Linux overcommit grants such an
// allocation without touching it, so the child process below caps its address space at
// 2 GiB: an allocation before the check throws std::bad_alloc there, as it does on hosts
// without overcommit or under ulimit -v (the apps then said just "std::bad_alloc").
TEST(WeightsFile, HugeClaimedLayerIsTruncationNotAnAllocation)
{
  RTLACAM_SKIP_UNDER_ASAN();
  std::vector<char> b(kWeightsMagic, kWeightsMagic + 8);
  for (uint32_t v : {kWeightsVersion, 32u, 4u, 5u, 2u, 65536u, 16900u})
    b.insert(b.end(), reinterpret_cast<char*>(&v), reinterpret_cast<char*>(&v) + 4);
  const std::string bad = temp_path("huge_layer.bin");
  write_bytes(bad, b);
  auto load_capped = [&] { test::exit_after_capped(1ul << 31, [&] { load_weights(bad); }); };
  EXPECT_EXIT(load_capped(), testing::ExitedWithCode(0),
              "truncated file: layer 0 weights needs 4430233600 bytes at offset 36, only 0 left");
}

TEST(WeightsFile, TrailingBytesAndNonFiniteValues)
{
  const std::string good = temp_path("good3.bin"), bad = temp_path("bad3.bin");
  save_weights(tiny_model(), good);
  std::vector<char> b = bytes_of(good);
  std::vector<char> c = b;
  c.push_back(0);
  write_bytes(bad, c);
  expect_error(bad, "1 unexpected trailing bytes");

  Model m = tiny_model();
  m.layers[1].w(2, 1) = std::numeric_limits<float>::quiet_NaN();
  save_weights(m, bad);
  expect_error(bad, "layer 1 weights has a non-finite value at index 7");
}

TEST(WeightsFile, AGoldenFileIsNotAWeightsFile)
{
  expect_error(RTLACAM_POLICY_MODELS "/random-32-32-20.golden", "bad magic");
}
