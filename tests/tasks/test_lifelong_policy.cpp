// Lifelong runs with the learned policy ordering PIBT's moves (CS-PIBT alone and inside
// RT-LaCAM): the policy follows goal changes through ActionPreference::set_goals, and
// every step stays valid.
#include <gtest/gtest.h>

#include "planner/movingai.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/lorr_problem.hpp"
#include "tasks/roundrobin.hpp"
#include "planner/solver.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;

TEST(LifelongPolicy, CspibtNeedsAPolicy)
{
  planner::Graph g = ttest::grid({"...."});
  EXPECT_THROW(planner::make_planner(planner::Solver::CsPibt, g, {0}, {3}), std::invalid_argument);
}

TEST(LifelongPolicy, PolicyRunsAreValidAndFinishErrands)
{
  const LorrProblem p = load_lorr_problem(ttest::kData + "/2023/random.domain/MR23-I-04.json");
  const planner::Graph g = planner::load_map(p.map_file);
  const planner::Config starts = load_lorr_agents(p.agent_file, g, p.team_size);
  auto file = std::make_shared<const TaskFile>(load_lorr_tasks(p.task_file, g));
  const policy::Model model = policy::load_weights(RTLACAM_POLICY_WEIGHTS);
  for (const std::string solver : {"cspibt", "rtlacam"}) {
    policy::PolicyPreference pref(g, model, planner::Config{});
    RoundRobin rr(file);
    LifelongOptions opt;
    opt.steps = 150;
    opt.budget = planner::Budget{50.0, 20};
    opt.solver.pref = &pref;
    const LifelongResult r = run_lifelong(g, starts, rr, solver, 0, opt);
    EXPECT_EQ(r.planner_errors, 0) << solver << ": " << r.first_error;
    EXPECT_GT(r.errands_finished, 100) << solver;  // 100 agents, 150 steps
    EXPECT_GT(pref.inferences(), 0) << solver;
  }
}
