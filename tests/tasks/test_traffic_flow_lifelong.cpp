// Lifelong runs with EPIBT ranked by online traffic-flow guide paths (--traffic-flow on):
// validator-clean executed steps whose letters replay (LoRR MAPF_T) to the robots' cells,
// more errands than without it on MR23-I-04 at 300 steps; bad options are one line, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "planner/validator.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/roundrobin.hpp"
#include "planner/solver.hpp"
#include "tasks_test_util.hpp"
#include "temp_path.hpp"

using namespace tasks;
using planner::Config;

TEST(TrafficFlowLifelong, StepsAreValidLorrActionsAndItFinishesMoreErrands)
{
  const ttest::Lorr L("/2023/random.domain/MR23-I-04.json");  // 100 robots, random-32-32-20
  const planner::Graph& g = L.g;
  long errands[2] = {0, 0};
  for (int on = 0; on < 2; ++on) {
    RoundRobin rr(L.file);
    LifelongOptions opt;
    opt.steps = 300;
    opt.budget = planner::Budget::unlimited();  // no deadline: the run does not depend on timing
    opt.action_model = ActionModel::Rotation;
    opt.record_actions = true;
    opt.solver.guidance = planner::arrow_guidance(g, 1, 3, 1);  // the app's default for epibt
    opt.solver.epibt.tf.on = on == 1;
    const LifelongResult r = run_lifelong(g, L.starts, rr, "epibt", 0, opt);
    EXPECT_EQ(r.planner_errors, 0) << r.first_error;
    errands[on] = r.errands_finished;
    std::vector<Config> at(static_cast<size_t>(opt.steps) + 1, L.starts);
    std::vector<int> h(L.starts.size(), 0);  // all start facing east
    for (long t = 1; t <= opt.steps; ++t) {
      at[t] = at[t - 1];
      for (size_t i = 0; i < L.starts.size(); ++i) {
        const char a = r.actions[i][static_cast<size_t>(t - 1)];
        at[t][i] = ttest::apply(g, at[t - 1][i], h[i], a);
        ASSERT_GE(at[t][i], 0) << "agent " << i << " forward into a wall at step " << t;
      }
      ASSERT_EQ(planner::Validator::check_transition(g, at[t - 1], at[t]), "") << "step " << t;
    }
    EXPECT_EQ(h, r.final_headings);
    for (const Event& e : r.events) {
      const auto& errs = L.file->tasks[static_cast<size_t>(e.task % L.file->size())];
      EXPECT_EQ(at[static_cast<size_t>(e.t)][e.agent], errs[static_cast<size_t>(e.errand)]);
    }
  }
  EXPECT_GT(errands[1], errands[0]) << "with traffic flow " << errands[1] << " vs without " << errands[0];
  std::cerr << "errands in 300 steps: epibt+arrows " << errands[0] << ", + traffic flow " << errands[1] << "\n";
}

TEST(TrafficFlowLifelong, BadOptionsAreOneLineAndExitCode2)
{
  const std::string p = ttest::kData + "/2023/random.domain/MR23-I-04.json --action-model rotation --steps 5 --quiet";
  struct Bad {
    std::string args, names;
  };
  for (const Bad& b : {Bad{"--solver epibt --traffic-flow on --tf-weights 1", "--tf-weights"},
                       Bad{"--solver epibt --traffic-flow on --tf-weights 1,-2", "--tf-weights"},
                       Bad{"--solver epibt --traffic-flow on --tf-weights a,b", "--tf-weights"},
                       Bad{"--solver pibt-rot --traffic-flow on", "--traffic-flow"},
                       Bad{"--solver epibt --traffic-flow maybe", "--traffic-flow"},
                       Bad{"--solver epibt --traffic-flow on --tf-refresh -1", "--tf-refresh"}}) {
    const std::string e = test::temp_path("tf.err");
    const int rc = std::system((std::string(RTLACAM_LIFELONG_BIN) + " --problem " + p + " " + b.args + " >/dev/null 2>" + e).c_str());
    ASSERT_TRUE(WIFEXITED(rc));
    EXPECT_EQ(WEXITSTATUS(rc), 2) << b.args;
    std::ifstream in(e);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string err = ss.str();
    EXPECT_NE(err.find(b.names), std::string::npos) << b.args << ": " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << b.args << ": " << err;
  }
}

TEST(TrafficFlowLifelong, OnByDefaultForEpibtOnly)
{
  const std::string p = ttest::kData + "/2023/random.domain/MR23-I-04.json --action-model rotation --steps 5 --quiet";
  auto json_of = [&p](const std::string& args) {
    const std::string o = test::temp_path("tf.json");
    const int rc = std::system((std::string(RTLACAM_LIFELONG_BIN) + " --problem " + p + " " + args + " >" + o + " 2>/dev/null").c_str());
    EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << args;
    std::ifstream in(o);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  const std::string ep = json_of("--solver epibt");
  EXPECT_NE(ep.find("\"trafficFlow\""), std::string::npos) << ep;
  EXPECT_NE(ep.find("\"active\": true"), std::string::npos) << ep;
  EXPECT_EQ(json_of("--solver epibt --traffic-flow off").find("\"trafficFlow\""), std::string::npos);
  EXPECT_EQ(json_of("--solver pibt-rot").find("\"trafficFlow\""), std::string::npos);
}
