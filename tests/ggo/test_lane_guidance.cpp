// LaneGuidance (tools/ggo): the parameterisation GGO searches maps to a valid Guidance; the
// committed optimised files (data/guidance/) load and drive a clean lifelong epibt run; the
// fitness is deterministic; rtlacam-ggo runs end to end.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_run.hpp"
#include "ggo/fitness.hpp"
#include "ggo/lane_guidance.hpp"
#include "grid.hpp"
#include "planner/error.hpp"
#include "planner/movingai.hpp"
#include "planner/rng.hpp"
#include "temp_path.hpp"

namespace {

const std::string kLorr = std::string(RTLACAM_TEST_DATA) + "/tasks/lorr/2023/random.domain";
const std::string kMap = kLorr + "/maps/random-32-32-20.map";

Eigen::VectorXd random_params(int n, double scale, uint64_t seed)
{
  planner::Rng rng(seed);
  Eigen::VectorXd p(n);
  for (int i = 0; i < n; ++i) p[i] = scale * (static_cast<double>(rng.below(2001)) / 1000.0 - 1.0);
  return p;
}

TEST(LaneGuidance, ZeroIsTheArrowFieldTimesUnit)
{
  const planner::Graph g = planner::load_map(kMap);
  const planner::Guidance arrows = planner::arrow_guidance(g, 1, 3, 1);
  for (int unit : {1, 4}) {
    const ggo::LaneGuidance lanes(g, unit);
    EXPECT_EQ(lanes.dims(), 2 * (32 + 32) + 1);
    const planner::Guidance gd = lanes.to_guidance(g, Eigen::VectorXd::Zero(lanes.dims()));
    ASSERT_EQ(gd.forward.size(), arrows.forward.size());
    for (size_t k = 0; k < gd.forward.size(); ++k) ASSERT_EQ(gd.forward[k], unit * arrows.forward[k]) << k;
    EXPECT_EQ(gd.turn, unit * arrows.turn);
  }
}

TEST(LaneGuidance, OneParameterMovesOneLaneDirection)
{
  const planner::Graph g = planner::load_map(kMap);
  const ggo::LaneGuidance lanes(g, 1);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(lanes.dims());
  p[lanes.index(0, 5, 2)] = std::log(10.0);  // row 5, west
  const planner::Guidance a = lanes.to_guidance(g, Eigen::VectorXd::Zero(lanes.dims())), b = lanes.to_guidance(g, p);
  int changed = 0;
  for (planner::Vertex v = 0; v < g.size(); ++v)
    for (int o = 0; o < 4; ++o) {
      const size_t k = static_cast<size_t>(v) * 4 + o;
      if (g.cell_y(v) == 5 && o == 2) {
        EXPECT_EQ(b.forward[k], 10 * a.forward[k]);
        ++changed;
      } else {
        EXPECT_EQ(b.forward[k], a.forward[k]);
      }
    }
  EXPECT_GT(changed, 10);
  EXPECT_EQ(lanes.index(3, 0, 1), 64 + 6);  // columns after the 2 x 32 row parameters
  EXPECT_EQ(lanes.index(3, 0, 3), 64 + 7);
}

TEST(LaneGuidance, AnyParametersGiveCostsInRangeAndRoundTrip)
{
  const planner::Graph g = planner::load_map(kMap);
  const ggo::LaneGuidance lanes(g, 4);
  for (uint64_t s = 0; s < 5; ++s) {
    Eigen::VectorXd p = random_params(lanes.dims(), 8.0, s);  // far beyond the clamps
    if (s == 4) p.setConstant(1e6);                            // exp overflows
    const planner::Guidance gd = lanes.to_guidance(g, p);
    for (uint16_t c : gd.forward) ASSERT_TRUE(c >= 1 && c <= planner::Guidance::kMaxCost);
    ASSERT_TRUE(gd.turn >= 1 && gd.turn <= planner::Guidance::kMaxCost);
    const std::string f = test::temp_path("lane_" + std::to_string(s) + ".guidance");
    planner::save_guidance(g, gd, f, "made by a test\nsecond header line");
    const planner::Guidance back = planner::load_guidance(g, f);
    EXPECT_EQ(back.forward, gd.forward);
    EXPECT_EQ(back.turn, gd.turn);
  }
  std::ifstream in(test::temp_path("lane_0.guidance"));
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "# made by a test");
}

TEST(LaneGuidance, RejectsWrongSizeAndNonGrid)
{
  const planner::Graph g = planner::load_map(kMap);
  const ggo::LaneGuidance lanes(g);
  EXPECT_THROW(lanes.to_guidance(g, Eigen::VectorXd::Zero(3)), std::invalid_argument);
  EXPECT_THROW(ggo::LaneGuidance(g, 30), std::invalid_argument);  // 3 x unit over kMaxCost
}

TEST(Fitness, DeterministicAndCleanOnASmallRun)
{
  const ggo::Problem pr = ggo::load_problem(kLorr + "/MR23-I-04.json");
  const ggo::LaneGuidance lanes(pr.g, 1);
  const planner::Guidance gd = lanes.to_guidance(pr.g, random_params(lanes.dims(), 0.5, 1));
  const ggo::Evaluation a = ggo::evaluate(pr, gd, 150, 0), b = ggo::evaluate(pr, gd, 150, 0);
  EXPECT_EQ(a.throughput, b.throughput);
  EXPECT_GT(a.throughput, 0.5);
  EXPECT_EQ(a.planner_errors, 0);
}

// Every committed optimised guidance loads on its map and gives a lifelong epibt run with
// every move validated (numPlannerErrors 0) and errands done.
TEST(CommittedGuidance, LoadsAndRunsClean)
{
  int files = 0;
  const ggo::Problem pr = ggo::load_problem(kLorr + "/MR23-I-04.json");
  for (const auto& e : std::filesystem::directory_iterator(RTLACAM_GUIDANCE_DIR)) {
    if (e.path().extension() != ".guidance" || e.path().filename().string().rfind("random-32-32-20", 0) != 0) continue;
    ++files;
    const planner::Guidance gd = planner::load_guidance(pr.g, e.path().string());
    EXPECT_FALSE(gd.uniform()) << e.path();
    const ggo::Evaluation r = ggo::evaluate(pr, gd, 200, 0);
    EXPECT_EQ(r.planner_errors, 0) << e.path();
    EXPECT_GT(r.throughput, 1.0) << e.path();
  }
  EXPECT_GE(files, 1);
}

TEST(GgoCli, RunsAGenerationAndWritesALoadableFile)
{
  const std::string out = test::temp_path("ggo.guidance"), log = test::temp_path("ggo.log");
  const std::string params = test::temp_path("ggo.guidance.params"), mean = test::temp_path("ggo.guidance.mean.params");
  const test::CliResult r = test::run_cli(RTLACAM_GGO_BIN, "--problem " + kLorr + "/MR23-I-04.json --steps 60 --generations 1 --lambda 2 --unit 1 --out " + out + " --log " + log);
  ASSERT_EQ(r.code, 0) << r.err;
  const planner::Graph g = planner::load_map(kMap);
  const planner::Guidance gd = planner::load_guidance(g, out);
  EXPECT_FALSE(gd.uniform());
  std::ifstream in(log);
  int lines = 0;
  for (std::string l; std::getline(in, l);) lines += !l.empty() && l[0] != '#';
  EXPECT_EQ(lines, 1 + 1 + 2);  // header, start, two candidates
  for (const std::string& f : {params, mean}) {  // one parameter a line after a comment
    std::ifstream p(f);
    int n = 0;
    for (std::string l; std::getline(p, l);) n += !l.empty() && l[0] != '#';
    EXPECT_EQ(n, 129) << f;
  }
  // --init with a bad parameter file: one line naming file:line, exit 2.
  const std::string bad = test::temp_file("bad.params", "# x\n0.5\nabc\n");
  const test::CliResult b = test::run_cli(RTLACAM_GGO_BIN, "--problem " + kLorr + "/MR23-I-04.json --init " + bad + " --out " + out + " --log " + log);
  EXPECT_EQ(b.code, 2);
  EXPECT_NE(b.err.find(bad + ":3:"), std::string::npos) << b.err;
}

}  // namespace
