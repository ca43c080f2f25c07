// Model: the Eigen forward pass equals PyTorch on the committed golden file, and computes
// a hand-checked MLP exactly.
#include <gtest/gtest.h>

#include "planner/error.hpp"
#include "policy/actions.hpp"
#include "policy/golden_file.hpp"
#include "policy/weights_file.hpp"
#include "temp_path.hpp"

using namespace policy;

TEST(Model, EigenEqualsPyTorchOnTheGoldenFile)
{
  const Model m = load_weights(RTLACAM_POLICY_MODELS "/random-32-32-20.bin");
  const Golden g = load_golden(RTLACAM_POLICY_MODELS "/random-32-32-20.golden");
  ASSERT_EQ(g.x.rows(), m.input_size());
  ASSERT_EQ(g.logits.rows(), kNumActions);
  ASSERT_GE(g.x.cols(), 100);
  Eigen::MatrixXf logits;
  m.forward(g.x, logits);
  ASSERT_EQ(logits.rows(), g.logits.rows());
  ASSERT_EQ(logits.cols(), g.logits.cols());
  const float diff = (logits - g.logits).cwiseAbs().maxCoeff();
  EXPECT_LT(diff, 1e-5f);
  // Batching does not change results: one column at a time gives the same logits.
  for (int k = 0; k < 5; ++k) {
    Eigen::MatrixXf one;
    m.forward(g.x.col(k), one);
    EXPECT_LT((one - g.logits.col(k)).cwiseAbs().maxCoeff(), 1e-5f);
  }
  // The golden inputs are observations: every value a multiple of 1/8 in [-1, 1].
  EXPECT_LE(g.x.cwiseAbs().maxCoeff(), 1.0f);
  EXPECT_EQ((g.x * 8.0f).array().round().matrix(), g.x * 8.0f);
}

TEST(Model, CommittedModelIsSmall)
{
  const Model m = load_weights(RTLACAM_POLICY_MODELS "/random-32-32-20.bin");
  EXPECT_EQ(m.spec.radius, 4);
  EXPECT_EQ(m.input_size(), 4 * 9 * 9);
  EXPECT_LT(m.num_parameters() * sizeof(float), 5u << 20);
}

// 2 inputs -> 2 hidden (ReLU) -> 5, by hand: h = relu([x0 - x1, x1 - x0] + [0, 1]).
TEST(Model, HandCheckedForward)
{
  Model m;
  Dense a, b;
  a.w.resize(2, 2);
  a.w << 1, -1, -1, 1;
  a.b.resize(2);
  a.b << 0, 1;
  b.w.resize(5, 2);
  b.w << 1, 0, 0, 1, 1, 1, -1, 0, 2, -3;
  b.b.resize(5);
  b.b << 0, 0, 0, 0, 0.5f;
  m.layers = {a, b};
  Eigen::MatrixXf x(2, 2), out;
  x << 3, 0, 1, 2;  // columns (3, 1) and (0, 2)
  m.forward(x, out);
  // (3,1): h = (2, 0) -> (2, 0, 2, -2, 4.5);  (0,2): h = (0, 3) -> (0, 3, 3, 0, -8.5)
  Eigen::MatrixXf want(5, 2);
  want << 2, 0, 0, 3, 2, 3, -2, 0, 4.5f, -8.5f;
  EXPECT_EQ(out, want);
}

TEST(GoldenFile, ErrorsNameTheFile)
{
  const std::string p = RTLACAM_POLICY_MODELS "/random-32-32-20.bin";
  try {
    load_golden(p);
    FAIL();
  } catch (const planner::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(p + ": not a policy golden file", 0), 0u) << e.what();
  }
}

// A 24-byte header claiming 1e6 samples x 65536 inputs (262 GB) with no data behind it is
// a truncated file, found before allocating (it used to escape as std::bad_alloc).
TEST(GoldenFile, HugeClaimedShapeIsTruncationNotBadAlloc)
{
  std::string bytes(kGoldenMagic, 8);
  for (uint32_t v : {kGoldenVersion, 1000000u, 65536u, 5u}) bytes.append(reinterpret_cast<const char*>(&v), 4);
  const std::string p = test::temp_file("huge.golden", bytes);
  try {
    load_golden(p);
    FAIL();
  } catch (const planner::InputError& e) {
    EXPECT_EQ(std::string(e.what()), p + ": truncated file: inputs needs 262144000000 bytes at offset 24, only 0 left");
  }
}
