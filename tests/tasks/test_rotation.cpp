// The rotation action model (LoRR MAPF_T): RotationExecution turns committed cell moves into
// F/R/C/W actions (a step per quarter turn, plan order per cell), and a lifelong run with it
// stays validator-clean; the actions replay to the robots' real cells and every event
// happens on its errand's cell. Also the LoRR log of such a run (lorr_log).
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "planner/movingai.hpp"
#include "planner/validator.hpp"
#include "tasks/lifelong_log.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_problem.hpp"
#include "tasks/roundrobin.hpp"
#include "executor/rotation_execution.hpp"
#include "tasks/task_pool.hpp"
#include "cli_run.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;
using executor::RotationExecution;
using executor::RotationRun;
using executor::run_with_rotation;
using planner::Config;

namespace {

// One tick, and the LoRR letters it executed.
const std::string& step(RotationExecution& ex)
{
  ex.step();
  return ex.actions();
}

std::string run_until_idle(RotationExecution& ex, int max_steps, int agent)
{
  std::string acts;
  for (int s = 0; s < max_steps; ++s) acts += step(ex)[static_cast<size_t>(agent)];
  return acts;
}

}  // namespace

TEST(RotationExecution, TurnsCostAStepAndRobotsStartFacingEast)
{
  const auto g = ttest::grid({"...", "..."});
  RotationExecution ex(g, {g.at(0, 0)}, 8);
  ex.push({g.at(1, 0)});  // east: straight ahead
  ex.push({g.at(1, 1)});  // south: one clockwise turn first
  ex.push({g.at(0, 1)});  // west: one more clockwise turn
  EXPECT_EQ(run_until_idle(ex, 6, 0), "FRFRFW");
  EXPECT_EQ(ex.positions()[0], g.at(0, 1));
  EXPECT_EQ(ex.headings()[0], 2);
  RotationExecution back(g, {g.at(1, 0)}, 8);
  back.push({g.at(0, 0)});  // behind it: a half turn (two steps), then forward
  EXPECT_EQ(run_until_idle(back, 4, 0), "RRFW");
  RotationExecution up(g, {g.at(0, 1)}, 8);
  up.push({g.at(0, 0)});  // north: counter-clockwise
  EXPECT_EQ(run_until_idle(up, 2, 0), "CF");
}

TEST(RotationExecution, FollowersMoveTogetherAndWaitForTheCellsEarlierVisitor)
{
  const auto g = ttest::grid({"....", "...."});
  // A (0,0) and B (1,0) both go east: B leaves the cell A enters in the same step.
  RotationExecution ex(g, {g.at(0, 0), g.at(1, 0)}, 8);
  ex.push({g.at(1, 0), g.at(2, 0)});
  EXPECT_EQ(step(ex), "FF");
  // Now B turns south first (a step) while A wants B's cell: A waits for B to leave.
  ex.push({g.at(2, 0), g.at(2, 1)});
  EXPECT_EQ(step(ex), "WR");
  EXPECT_EQ(step(ex), "FF");
  EXPECT_EQ(ex.positions(), (Config{g.at(2, 0), g.at(2, 1)}));
}

TEST(RotationExecution, WindowBoundsHowFarThePlanRunsAhead)
{
  const auto g = ttest::grid({"....."});
  RotationExecution ex(g, {g.at(4, 0)}, 2);  // must turn around: two steps before its first move
  EXPECT_TRUE(ex.can_accept());
  ex.push({g.at(3, 0)});
  ex.push({g.at(2, 0)});
  EXPECT_FALSE(ex.can_accept());
  ex.step(), ex.step();
  EXPECT_FALSE(ex.can_accept());  // still turning
  ex.step();                      // first move
  EXPECT_TRUE(ex.can_accept());
}

TEST(RotationExecution, RandomValidPlansExecuteWithoutConflictsInPlanOrder)
{
  // Random cell-space plans (random valid steps of 12 robots on a 6x6 grid), executed with
  // turns: every executed step passes the validator, each robot visits the plan's cells in
  // order, and all reach the plan's last configuration (no deadlock).
  const auto g = ttest::grid({"......", "......", "..#...", "......", "...#..", "......"});
  planner::Rng rng(7);
  Config c;
  for (int v = 0; v < g.size() && c.size() < 12; v += 3) c.push_back(v);
  for (int trial = 0; trial < 20; ++trial) {
    RotationExecution ex(g, c, 4);
    std::vector<std::vector<planner::Vertex>> plan_cells(c.size()), done_cells(c.size());
    for (size_t i = 0; i < c.size(); ++i) plan_cells[i].push_back(c[i]), done_cells[i].push_back(c[i]);
    Config cur = c;
    int pushed = 0;
    for (int step = 0; step < 400; ++step) {
      if (pushed < 60 && ex.can_accept()) {
        Config next = cur;  // each robot tries a random neighbour, kept if the step stays valid
        for (size_t i = 0; i < cur.size(); ++i) {
          const auto nb = g.neighbors(cur[i]);
          Config trial_c = next;
          trial_c[i] = nb[static_cast<size_t>(rng.uniform() * static_cast<float>(nb.size())) % nb.size()];
          if (planner::Validator::check_transition(g, cur, trial_c).empty()) next = trial_c;
        }
        ASSERT_EQ(planner::Validator::check_transition(g, cur, next), "");
        for (size_t i = 0; i < cur.size(); ++i)
          if (next[i] != cur[i]) plan_cells[i].push_back(next[i]);
        ex.push(next);
        cur = next;
        ++pushed;
      }
      const Config before = ex.positions();
      ex.step();
      ASSERT_EQ(planner::Validator::check_transition(g, before, ex.positions()), "") << "trial " << trial << " step " << step;
      for (size_t i = 0; i < cur.size(); ++i)
        if (ex.positions()[i] != before[i]) done_cells[i].push_back(ex.positions()[i]);
    }
    EXPECT_EQ(ex.positions(), cur) << "trial " << trial;
    EXPECT_EQ(done_cells, plan_cells) << "trial " << trial;
    c = cur;
  }
}

TEST(RotationRun, LifelongRunIsValidAndEventsHappenOnTheRobotsRealCells)
{
  const ttest::Lorr L("/2023/random.domain/MR23-I-04.json");
  const planner::Graph& g = L.g;
  const Config& starts = L.starts;
  const auto& file = L.file;
  RoundRobin rr(file);
  LifelongOptions opt;
  opt.steps = 150;
  opt.budget = planner::Budget::expansion_count(50);
  opt.action_model = ActionModel::Rotation;
  opt.record_actions = true;
  const LifelongResult r = run_lifelong(g, starts, rr, "rtlacam", 1, opt);
  EXPECT_EQ(r.planner_errors, 0) << r.first_error;
  ASSERT_GT(r.errands_finished, 20);
  // Replay: cells per step from the letters.
  std::vector<Config> at(static_cast<size_t>(opt.steps) + 1, starts);
  std::vector<int> h(starts.size(), 0);
  size_t turns = 0;
  for (long t = 1; t <= opt.steps; ++t) {
    at[t] = at[t - 1];
    for (size_t i = 0; i < starts.size(); ++i) {
      const char a = r.actions[i][static_cast<size_t>(t - 1)];
      ASSERT_TRUE(a == 'F' || a == 'R' || a == 'C' || a == 'W') << a;
      turns += a == 'R' || a == 'C';
      at[t][i] = ttest::apply(g, at[t - 1][i], h[i], a);
      ASSERT_GE(at[t][i], 0);
    }
    ASSERT_EQ(planner::Validator::check_transition(g, at[t - 1], at[t]), "") << "step " << t;
  }
  EXPECT_GT(turns, 0u);
  EXPECT_EQ(h, r.final_headings);
  for (const Event& e : r.events) {
    const auto& errands = file->tasks[static_cast<size_t>(e.task % file->size())];
    EXPECT_EQ(at[static_cast<size_t>(e.t)][e.agent], errands[static_cast<size_t>(e.errand)]);
  }
}

TEST(LorrLog, PoolEventsCountErrandsDoneAndScheduleTasksThatExist)
{
  const ttest::Lorr L("/2024/random.domain/RANDOM-01.json");
  const LorrProblem& pr = L.p;
  const planner::Graph& g = L.g;
  const Config& starts = L.starts;
  const auto& file = L.file;
  TaskPool pool(file, g, pr.pool_size(), make_assigner("greedy", 32));
  LifelongOptions opt;
  opt.steps = 120;
  opt.budget = planner::Budget::expansion_count(20);
  opt.action_model = ActionModel::Rotation;
  opt.record_actions = true;
  const LifelongResult r = run_lifelong(g, starts, pool, "rtlacam", 0, opt);
  const nlohmann::json j = lorr_log({"p", "rtlacam", "pool", "greedy", pr.team_size, 0, 0}, r, pool, g);
  EXPECT_EQ(j["version"], "2024 LoRR");
  EXPECT_EQ(j["actionModel"], "MAPF_T");
  EXPECT_EQ(j["plannerTimes"].size(), 120u);
  ASSERT_EQ(j["events"].size(), r.events.size());
  std::map<long, nlohmann::json> tasks;
  for (const auto& t : j["tasks"]) tasks[t[0].get<long>()] = t;
  ASSERT_GT(r.events.size(), 0u);
  for (size_t k = 0; k < r.events.size(); ++k) {
    const auto& e = j["events"][k];
    EXPECT_EQ(e[3].get<int>(), r.events[k].errand + 1);  // LoRR: errands done, 1 for the first
    ASSERT_TRUE(tasks.count(e[2].get<long>()));
    EXPECT_LE(tasks[e[2].get<long>()][1].get<long>(), e[0].get<long>());  // revealed before it finished
  }
  std::set<long> scheduled;
  for (const auto& s : j["actualSchedule"]) {
    const std::string str = s;
    size_t p = 0;
    while (p < str.size()) {
      const size_t colon = str.find(':', p), comma = str.find(',', p);
      const long task = std::stol(str.substr(colon + 1, comma - colon - 1));
      if (task >= 0) { EXPECT_TRUE(tasks.count(task)) << task; }
      scheduled.insert(task);
      p = comma == std::string::npos ? str.size() : comma + 1;
    }
  }
  EXPECT_GE(scheduled.size(), static_cast<size_t>(pr.team_size));
}

TEST(LorrLog, RoundRobinTaskIdsAreLorrsAssignmentCounter)
{
  const ttest::Lorr L("/2023/random.domain/MR23-I-04.json");
  const LorrProblem& pr = L.p;
  const planner::Graph& g = L.g;
  const Config& starts = L.starts;
  const auto& file = L.file;
  RoundRobin rr(file);
  LifelongOptions opt;
  opt.steps = 100;
  opt.budget = planner::Budget::expansion_count(20);
  opt.record_actions = true;
  const LifelongResult r = run_lifelong(g, starts, rr, "rtlacam", 0, opt);
  const nlohmann::json j = lorr_log({"p", "rtlacam", "roundrobin", "greedy", pr.team_size, 0, 0}, r, rr, g);
  EXPECT_EQ(j["version"], "2023 LoRR");
  EXPECT_EQ(j["actionModel"], "MAPF");
  const auto& ts = j["tasks"];
  ASSERT_EQ(ts.size(), static_cast<size_t>(pr.team_size + r.tasks_finished));  // one more per finished task
  for (size_t i = 0; i < ts.size(); ++i) EXPECT_EQ(ts[i][0].get<size_t>(), i);
  // First tasks: agent a gets LoRR task a at t = 0; finished events name the task it held.
  long finished = 0;
  for (int a = 0; a < pr.team_size; ++a) {
    const auto& ev = j["events"][static_cast<size_t>(a)];
    ASSERT_GE(ev.size(), 1u);
    EXPECT_EQ(ev[0], nlohmann::json({a, 0, "assigned"}));
    long held = a;
    for (size_t k = 1; k < ev.size(); ++k) {
      if (ev[k][2] == "finished") {
        EXPECT_EQ(ev[k][0].get<long>(), held);
        ++finished;
      } else {
        held = ev[k][0].get<long>();
      }
    }
  }
  EXPECT_EQ(finished, r.tasks_finished);
}

TEST(RotationRun, OneShotPlanRunsWithHeadingsAndTurnsCostSteps)
{
  const auto g = ttest::grid({"....", "....", "...."});
  // Two robots cross paths in cell space; with headings it takes longer but stays valid.
  std::vector<Config> plan = {{g.at(0, 0), g.at(3, 2)}, {g.at(1, 0), g.at(3, 1)}, {g.at(1, 1), g.at(3, 0)},
                              {g.at(1, 2), g.at(2, 0)}};
  const RotationRun r = run_with_rotation(g, plan);
  EXPECT_EQ(r.error, "");
  // Robot 0: F, R, F, F (4 steps). Robot 1 faces east, must face north: C, F, F, C, F (5).
  EXPECT_EQ(r.makespan, 5);
  EXPECT_EQ(r.soc, 9);
  EXPECT_EQ(r.turns, 3);
}

TEST(RotationRun, BenchReportsTheRotationRunOfTheExecutedPlan)
{
  const std::string dir = RTLACAM_TEST_DATA "/planner/";
  const auto r = test::run_cli(RTLACAM_BENCH_BIN, "--map " + dir + "random-32-32-20.map --scen " + dir +
                                                      "random-32-32-20-random-1.scen -N 50 --solver rtlacam --json "
                                                      "--budget-expansions 10 --action-model rotation");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["action_model"], "rotation");
  EXPECT_EQ(j["valid"], true);
  EXPECT_TRUE(j["solved"].get<bool>());
  EXPECT_GE(j["rotation_makespan"].get<long>(), j["makespan"].get<long>());  // turns only add steps
  EXPECT_GT(j["rotation_soc"].get<long>(), j["soc"].get<long>());
  EXPECT_GT(j["rotation_turns"].get<long>(), 0);
}

TEST(LifelongTiming, EpochStartIsChargedToTheStepAfterACompletion)
{
  const ttest::Lorr L("/2023/random.domain/MR23-I-04.json");
  const planner::Graph& g = L.g;
  const Config& starts = L.starts;
  RoundRobin rr(L.file);
  LifelongOptions opt;
  opt.steps = 80;
  opt.budget = planner::Budget::expansion_count(5);
  std::vector<StepRecord> recs;
  opt.on_step = [&](const StepRecord& s) { recs.push_back(s); };
  const LifelongResult r = run_lifelong(g, starts, rr, "rtlacam", 0, opt);
  ASSERT_EQ(r.epoch_start_ms.size(), 80u);
  int charged = 0;
  for (size_t k = 0; k < recs.size(); ++k) {
    const bool after_completion = k > 0 && recs[k - 1].completed > 0;
    EXPECT_EQ(r.epoch_start_ms[k] > 0, after_completion) << "step " << k + 1;
    EXPECT_LE(r.epoch_start_ms[k], r.planner_ms[k]);
    charged += after_completion;
  }
  EXPECT_GT(charged, 10);
}

TEST(HeadingPreference, TurnAwareCostCountsTurnsAndTheStepSpentWaiting)
{
  // Open 5 x 5 grid, robot on (2, 2) facing east (LoRR start), goal two cells north.
  const auto g = ttest::grid({".....", ".....", ".....", ".....", "....."});
  const planner::Vertex v = g.at(2, 2);
  HeadingPreference pref(g, {v}, HeadingCost::Turns);
  pref.set_goals({g.at(2, 0)});
  EXPECT_EQ(pref.cost_to_go(0, v, 0), 2 + 1);        // facing east: one turn, two steps
  EXPECT_EQ(pref.cost_to_go(0, v, 3), 2);            // facing north: straight
  EXPECT_EQ(pref.cost_to_go(0, g.at(2, 0), 1), 0);   // on the goal: no turn needed
  planner::Rng rng(1);
  std::map<std::string, float> s;
  for (int k = 0; k < 20; ++k) {  // the tie-break noise never reorders whole steps
    const float north = pref.score(0, v, g.at(2, 1), rng), stay = pref.score(0, v, v, rng);
    const float east = pref.score(0, v, g.at(3, 2), rng), south = pref.score(0, v, g.at(2, 3), rng);
    EXPECT_LT(north, stay);   // turn + forward (3 steps to go) beats waiting (1 + 3)
    EXPECT_LT(stay, east);    // east: no turn now, but a detour and a turn later (5)
    EXPECT_LT(east, south);   // south: a turn, then a half turn back (7)
  }
  // After a committed move north the robot faces north: straight on costs no turn.
  pref.committed({g.at(2, 1)});
  EXPECT_LT(pref.score(0, g.at(2, 1), g.at(2, 0), rng), 2.0f);
  // Deeper in the tree (not the frontier cell) the heading is unknown: plain distance.
  EXPECT_GE(pref.score(0, g.at(4, 4), g.at(4, 3), rng), 5.0f);
  EXPECT_LT(pref.score(0, g.at(4, 4), g.at(4, 3), rng), 6.0f);
}

TEST(HeadingPreference, BothOrdersRunValidatorCleanLifelong)
{
  const ttest::Lorr L("/2023/random.domain/MR23-I-04.json");
  for (HeadingCost c : {HeadingCost::Ties, HeadingCost::Turns}) {
    RoundRobin rr(L.file);
    LifelongOptions opt;
    opt.steps = 150;
    opt.budget = planner::Budget::expansion_count(5);
    opt.action_model = ActionModel::Rotation;
    opt.heading_cost = c;
    const LifelongResult r = run_lifelong(L.g, L.starts, rr, "rtlacam", 0, opt);
    EXPECT_EQ(r.planner_errors, 0) << r.first_error;
    EXPECT_GT(r.errands_finished, 40);
  }
}
