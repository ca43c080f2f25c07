// Lifelong runs through the executor (tasks/lifelong_exec.hpp): without delays lockstep is
// exactly the plain runner; under delays every executed step is valid, errands keep
// completing, and rtlacam-lifelong rejects bad delay switches with one line.
#include <gtest/gtest.h>

#include "cli_run.hpp"
#include "planner/heading.hpp"
#include "planner/movingai.hpp"
#include "tasks/lifelong_exec.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/lorr_problem.hpp"
#include "tasks/task_pool.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;

namespace {

const char* const kRandom01 = "/2024/random.domain/RANDOM-01.json";

std::unique_ptr<TaskPool> make_pool(const ttest::Lorr& L)
{
  return std::make_unique<TaskPool>(L.file, L.g, L.p.pool_size(), make_assigner("greedy"), false);
}

LifelongOptions options(long steps)
{
  LifelongOptions opt;
  opt.steps = steps;
  opt.budget = planner::Budget{0, 50};  // expansions only: deterministic
  return opt;
}

}  // namespace

TEST(LifelongExec, LockstepWithoutDelaysIsThePlainRunner)
{
  const ttest::Lorr L(kRandom01);
  auto a = make_pool(L), b = make_pool(L);
  const LifelongResult plain = run_lifelong(L.g, L.starts, *a, "rtlacam", 0, options(200));
  executor::ExecOptions o;
  o.mode = "lockstep";
  const LifelongExecResult x = run_lifelong_exec(L.g, L.starts, *b, "rtlacam", 0, options(200), {}, o);
  EXPECT_EQ(x.life.planner_errors, 0) << x.life.first_error;
  EXPECT_GT(plain.errands_finished, 50);
  EXPECT_EQ(x.life.errands_finished, plain.errands_finished);
  ASSERT_EQ(x.life.events.size(), plain.events.size());
  for (size_t k = 0; k < plain.events.size(); ++k) {
    EXPECT_EQ(x.life.events[k].t, plain.events[k].t);
    EXPECT_EQ(x.life.events[k].agent, plain.events[k].agent);
  }
}

TEST(LifelongExec, AdgUnderDelaysKeepsCompletingErrands)
{
  const ttest::Lorr L(kRandom01);
  for (double p : {0.01, 0.05}) {
    auto pool = make_pool(L);
    executor::DelaySpec d;
    d.kind = "bernoulli";
    d.p = p;
    d.min_ticks = 1;
    d.max_ticks = 5;
    d.slow = {{0, 0.5}};
    executor::ExecOptions o;
    o.window = 4;
    const LifelongExecResult x = run_lifelong_exec(L.g, L.starts, *pool, "rtlacam", 0, options(400), d, o);
    EXPECT_EQ(x.life.planner_errors, 0) << x.life.first_error;  // every executed step valid
    EXPECT_GT(x.life.errands_finished, 50) << p;
    EXPECT_LT(x.max_gap, 60) << p;  // errands keep completing
    EXPECT_GT(x.exec.delay_ticks, 0);
  }
}

TEST(LifelongExec, CliRejectsBadDelaySwitchesWithOneLine)
{
  const std::string prob = "--problem " + ttest::kData + "/2024/random.domain/RANDOM-01.json --steps 5 --quiet ";
  for (const std::string bad : {"--executor adg --delay-kind bernoulli --delay-p 1.5", "--executor adg --window 0",
                                "--executor adg --delay-min 3 --delay-max 2", "--delay-p 0.1 --delay-kind bernoulli",
                                "--executor adg --slow 0:2", "--executor adg --stuck 0:1"}) {
    const test::CliResult r = test::run_cli(RTLACAM_LIFELONG_BIN, prob + bad);
    EXPECT_EQ(r.code, 2) << bad << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << "\n" << r.err;
  }
  const test::CliResult ok = test::run_cli(RTLACAM_LIFELONG_BIN, prob + "--executor adg --delay-kind bernoulli --delay-p 0.1");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("\"executor\""), std::string::npos);
}

// The rotation solvers under delays (the twin of the controller's rotation runs): their
// planned steps run on GraphExecution with executed headings. Every executed step is checked
// by the runner as LoRR actions (F only into the cell ahead of the executed heading, turns in
// place): a robot that moved without turning first fails it. Replaying the executed letters
// from the start must end on the final cells and headings.
TEST(LifelongExec, RotationSolversTurnBeforeTheyMoveUnderDelays)
{
  const ttest::Lorr L(kRandom01);
  for (const char* solver : {"pibt-rot", "wppl"})
    for (const char* mode : {"adg", "adg-follow", "lockstep"}) {
      auto pool = make_pool(L);
      executor::DelaySpec d;
      d.kind = "bernoulli";
      // (In lockstep one stopped robot holds all 100: far fewer stops keep it moving.)
      const bool lock = std::string(mode) == "lockstep";
      d.p = lock ? 0.0005 : 0.02;
      d.min_ticks = 1;
      d.max_ticks = 5;
      d.slow = {{0, 0.5}};
      executor::ExecOptions o;
      o.mode = mode;
      LifelongOptions opt = options(200);
      opt.action_model = ActionModel::Rotation;
      opt.record_actions = true;
      const LifelongExecResult x = run_lifelong_exec(L.g, L.starts, *pool, solver, 0, opt, d, o);
      const std::string tag = std::string(solver) + " " + mode;
      EXPECT_EQ(x.life.planner_errors, 0) << tag << ": " << x.life.first_error;
      EXPECT_GT(x.life.errands_finished, lock ? 15 : 30) << tag;
      EXPECT_GT(x.exec.delay_ticks, 0) << tag;
      EXPECT_GT(x.exec.turn_ticks, 0) << tag;
      // Replay the executed letters (LoRR's transition): every F into a cell, no two robots
      // on one cell, and the headings the run ended with.
      ASSERT_EQ(x.life.actions.size(), L.starts.size());
      std::vector<planner::Pose> s(L.starts.size());
      for (size_t i = 0; i < s.size(); ++i) s[i] = {L.starts[i], 0};  // LoRR: all face east
      size_t turns = 0;
      for (size_t t = 0; t < x.life.actions[0].size(); ++t) {
        std::vector<int> on(L.g.size(), -1);
        for (size_t i = 0; i < s.size(); ++i) {
          const char a = x.life.actions[i][t];
          s[i] = planner::result_state(L.g, s[i], a);
          turns += a == 'R' || a == 'C';
          ASSERT_GE(s[i].v, 0) << tag << " robot " << i << " step " << t;
          ASSERT_EQ(on[s[i].v], -1) << tag << " robots " << on[s[i].v] << ", " << i << " step " << t;
          on[s[i].v] = static_cast<int>(i);
        }
      }
      for (size_t i = 0; i < s.size(); ++i) EXPECT_EQ(s[i].heading, x.life.final_headings[i]) << tag << " robot " << i;
      EXPECT_GT(turns, 0u) << tag;
    }
}

// Without delays, lockstep runs the rotation solver's steps exactly as the plain runner does.
TEST(LifelongExec, RotationLockstepWithoutDelaysIsThePlainRunner)
{
  const ttest::Lorr L(kRandom01);
  auto a = make_pool(L), b = make_pool(L);
  LifelongOptions opt = options(200);
  opt.action_model = ActionModel::Rotation;
  const LifelongResult plain = run_lifelong(L.g, L.starts, *a, "pibt-rot", 0, opt);
  executor::ExecOptions o;
  o.mode = "lockstep";
  const LifelongExecResult x = run_lifelong_exec(L.g, L.starts, *b, "pibt-rot", 0, opt, {}, o);
  EXPECT_EQ(x.life.planner_errors, 0) << x.life.first_error;
  EXPECT_GT(plain.errands_finished, 50);
  ASSERT_EQ(x.life.events.size(), plain.events.size());
  for (size_t k = 0; k < plain.events.size(); ++k) {
    EXPECT_EQ(x.life.events[k].t, plain.events[k].t);
    EXPECT_EQ(x.life.events[k].agent, plain.events[k].agent);
  }
}

TEST(LifelongExec, CliRunsRotationSolversUnderDelaysAndRefusesACellPlanUnderRotation)
{
  const std::string prob = "--problem " + ttest::kData + "/2024/random.domain/RANDOM-01.json --steps 20 --quiet "
                           "--action-model rotation --executor adg --delay-kind bernoulli --delay-p 0.05 ";
  const test::CliResult ok = test::run_cli(RTLACAM_LIFELONG_BIN, prob + "--solver pibt-rot");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("\"turnTicks\""), std::string::npos);
  const test::CliResult bad = test::run_cli(RTLACAM_LIFELONG_BIN, prob + "--solver rtlacam");
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}
