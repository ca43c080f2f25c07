// The lifelong executor: progress epochs (a fresh tree exactly when an errand completes),
// validator-clean runs of all three solvers on a 100-agent LoRR instance, duplicate goals,
// throughput that does not stay at zero where PIBT livelocks, and LifelongEpochs, the epoch
// part a back end of its own (the SUMO controller) shares with LifelongRun.
#include <gtest/gtest.h>

#include <map>

#include "planner/movingai.hpp"
#include "tasks/greedy_assigner.hpp"
#include "tasks/lifelong_epochs.hpp"
#include "tasks/lifelong_goal.hpp"
#include "tasks/lifelong_run.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_problem.hpp"
#include "tasks/roundrobin.hpp"
#include "tasks/task_pool.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;
using planner::Config;

namespace {

// A scripted planner: moves along a fixed list of configurations, counts set_goals.
class Scripted : public planner::RealtimePlanner {
 public:
  explicit Scripted(std::vector<Config> script) : script_(std::move(script)), cur_(script_[0]) {}
  planner::Status search(const planner::Budget&) override { return planner::Status::Searching; }
  const Config& next() override { return script_[std::min(k_ + 1, script_.size() - 1)]; }
  void commit() override { cur_ = next(), ++k_; }
  void set_goals(const Config& g, planner::GoalTest) override { goals_ = g, ++resets, calls += 'g'; }
  void set_priority_hint(std::vector<float> h) override { hints.push_back(std::move(h)), calls += 'h'; }
  const Config& current() const override { return cur_; }
  const Config& goals() const override { return goals_; }
  bool at_goal() const override { return false; }
  uint64_t expansions() const override { return 0; }
  size_t explored() const override { return 0; }
  std::string name() const override { return "scripted"; }
  int resets = 0;
  std::vector<std::vector<float>> hints;  // set_priority_hint's, in order
  std::string calls;                      // 'h' a hint, 'g' set_goals, in order

 private:
  std::vector<Config> script_;
  Config cur_, goals_;
  size_t k_ = 0;
};

// Longest run of consecutive steps without a completion, counting the tail.
long longest_drought(const LifelongResult& r)
{
  long last = 0, worst = 0;
  for (const Event& e : r.events) worst = std::max(worst, e.t - last - 1), last = e.t;
  return std::max(worst, r.steps - last);
}

}  // namespace

TEST(Epochs, SetGoalsExactlyWhenAnErrandCompletes)
{
  const auto g = ttest::grid({"......"});
  auto file = ttest::task_file(g, {{{2, 0}}, {{5, 0}}, {{0, 0}}, {{4, 0}}});
  RoundRobin rr(file);
  LifelongResult r;
  LifelongEpochs epochs(rr, r);  // the seam of every back end (lifelong_epochs.hpp)
  epochs.start(g, {0, 5}, nullptr);
  Scripted p({{0, 5}, {1, 5}, {2, 4}, {2, 4}, {1, 3}, {0, 4}});
  std::vector<long> reset_steps;
  for (long t = 1; t <= 5; ++t) {
    p.commit();
    const int before = p.resets;
    const bool epoch = epochs.complete(t, p.current());
    if (epoch) epochs.start_epoch(p);
    epochs.record(epoch);
    const std::vector<Event>& ev = epochs.completed();
    EXPECT_EQ(p.resets - before, ev.empty() ? 0 : 1) << "t=" << t;
    if (!ev.empty()) {
      reset_steps.push_back(t);
      EXPECT_EQ(p.goals(), rr.goals());
    }
  }
  // t=1: agent 1 stays on x=5 (task 1) -> next task 3 (x=4).
  // t=2: agent 0 on x=2 (task 0) -> task 2 (x=0); agent 1 on x=4 (task 3) -> task 5 (x=5).
  // t=3, t=4: nobody on a goal. t=5: agent 0 on x=0 (task 2).
  EXPECT_EQ(reset_steps, (std::vector<long>{1, 2, 5}));
  EXPECT_EQ(rr.errands_finished(), 4);
  EXPECT_EQ(r.epochs, 4);  // the first goals' and three new ones'
  EXPECT_EQ(r.events.size(), 4u);
}

TEST(Epochs, RtLacamKeepsItsTreeUntilACompletion)
{
  ttest::Lorr L("/2023/random.domain/MR23-I-04.json");
  RoundRobin rr(L.file);
  LifelongOptions opt;
  opt.steps = 120;
  opt.budget = planner::Budget{50.0, 200};  // deterministic: expansions run out first
  std::vector<StepRecord> recs;
  opt.on_step = [&](const StepRecord& s) { recs.push_back(s); };
  const LifelongResult r = run_lifelong(L.g, L.starts, rr, "rtlacam", 0, opt);
  ASSERT_EQ(recs.size(), 120u);
  long with_completions = 0;
  for (size_t k = 0; k < recs.size(); ++k) {
    EXPECT_EQ(recs[k].new_epoch, recs[k].completed > 0);
    with_completions += recs[k].completed > 0;
    if (k == 0) continue;
    EXPECT_EQ(recs[k].epoch, recs[k - 1].epoch + (recs[k - 1].new_epoch ? 1 : 0));
    if (recs[k].epoch == recs[k - 1].epoch) {  // same tree: the explored table only grows
      EXPECT_GE(recs[k].explored, recs[k - 1].explored) << "step " << recs[k].t;
    }
  }
  EXPECT_EQ(r.epochs, 1 + with_completions);
  EXPECT_EQ(r.planner_errors, 0) << r.first_error;
  EXPECT_GT(r.errands_finished, 0);
}

// LifelongEpochs (lifelong_epochs.hpp) is the task and epoch part that the grid's LifelongRun
// and the SUMO controller share. A back end of its own -- here a loop that executes each
// committed step at once, as the controller's lockstep does -- calling only LifelongEpochs
// runs the same epochs as LifelongRun. Station queues change goals without a completion:
// those start epochs too.
TEST(LifelongEpochs, ABackEndOfItsOwnRunsTheSameEpochsAsLifelongRun)
{
  // A dead-end station at the top of a stub, a picking aisle below the cross aisle
  // (test_station_queues.cpp's stub): one agent at a time in the stub, the rest queue.
  const auto g = ttest::grid({"###.##", "###.##", "......", "###.##", "###.##", "###.##", "###.##", "......"});
  auto file = ttest::task_file(g, {{{3, 0}, {0, 7}}, {{3, 0}, {5, 7}}});
  const Config starts{g.at(0, 2), g.at(5, 2), g.at(1, 7), g.at(4, 7), g.at(0, 7), g.at(5, 7)};
  auto pool = [&] {
    auto p = std::make_unique<TaskPool>(file, g, 6, std::make_unique<GreedyAssigner>());
    p->set_queues(g, {1, 3, 0});
    p->set_urgency({true, false});  // stalled errands hinted at each epoch start
    return p;
  };
  const long steps = 150;
  LifelongOptions opt;
  opt.steps = steps;
  opt.budget = planner::Budget::expansion_count(30);
  auto grid_tasks = pool();
  LifelongRun run(g, starts, *grid_tasks, "rtlacam", 0, opt);
  while (!run.done()) run.step();
  const long long grid_gap = run.max_gap();
  const LifelongResult want = run.finish();

  // The other back end: the planner built as LifelongRun builds it, then per step search,
  // commit, and the epoch phases.
  auto tasks = pool();
  LifelongResult got;
  LifelongEpochs epochs(*tasks, got);
  const size_t cap = 2 * starts.size() + 256;
  auto cache = std::make_shared<planner::DistCache>(g, cap);
  epochs.start(g, starts, std::make_unique<FreeFlowBound>(cache), cache);
  planner::SolverOptions so = opt.solver;
  so.max_dist_tables = cap;
  auto p = planner::make_planner(planner::Solver::RtLacam, g, starts, tasks->goals(), so, lifelong_goal_test(*tasks, starts));
  p->share_dist_cache(cache);
  long completion_steps = 0;
  for (long t = 1; t <= steps; ++t) {
    p->search(opt.budget);
    p->next();
    p->commit();
    const bool epoch = epochs.complete(t, p->current());
    if (epoch) epochs.start_epoch(*p);
    epochs.record(epoch);
    epochs.count(t, p->current());
    completion_steps += !epochs.completed().empty();
  }
  EXPECT_EQ(got.events, want.events);
  EXPECT_EQ(got.epochs, want.epochs);
  EXPECT_EQ(epochs.max_gap(), grid_gap);
  EXPECT_EQ(tasks->errands_finished(), want.errands_finished);
  EXPECT_GE(want.errands_finished, 10);
  // Goals that changed without a completion (the queue moved up) started epochs too.
  EXPECT_GT(got.epochs, 1 + completion_steps);
  // The counts: one agent at a time heads for the station, the others wait on queue cells.
  const EpochCounts& n = epochs.counts();
  EXPECT_EQ(n.max_heading, 1);
  EXPECT_GT(n.queued_ticks, 20);
  EXPECT_LE(n.max_goal_ticks, steps);
  int idle = 0;
  for (int a = 0; a < tasks->num_agents(); ++a) idle += !tasks->busy(a);
  EXPECT_EQ(n.idle, idle);
  EXPECT_EQ(n.parked, 0);  // no parking cells
}

// Each epoch start hands the planner the task layer's priority hints first (urgency.hpp),
// then the new goals.
TEST(LifelongEpochs, EveryEpochStartHintsThePlannerBeforeItsNewGoals)
{
  const auto g = ttest::grid({"......"});
  auto file = ttest::task_file(g, {{{2, 0}}, {{5, 0}}, {{0, 0}}, {{4, 0}}});
  RoundRobin rr(file);
  rr.set_urgency({true, false});
  LifelongResult r;
  LifelongEpochs epochs(rr, r);
  epochs.start(g, {0, 5}, nullptr);
  EXPECT_NE(rr.stalls(), nullptr);  // start() watches the errands' stalls
  Scripted p({{0, 5}, {1, 5}, {2, 4}, {2, 4}, {1, 3}, {0, 4}});
  for (long t = 1; t <= 5; ++t) {
    p.commit();
    const bool epoch = epochs.complete(t, p.current());
    EXPECT_EQ(epoch, !epochs.completed().empty()) << "t=" << t;  // no queues: completions only
    if (epoch) epochs.start_epoch(p);
    epochs.record(epoch);
    EXPECT_EQ(p.hints.size(), static_cast<size_t>(p.resets)) << "t=" << t;
  }
  EXPECT_EQ(p.resets, 3);  // t = 1, 2, 5 (Epochs.SetGoalsExactlyWhenAnErrandCompletes)
  EXPECT_EQ(p.calls, "hghghg");
  EXPECT_EQ(r.epochs, 4);
  EXPECT_EQ(r.events.size(), 4u);
  for (const auto& h : p.hints) EXPECT_EQ(h.size(), 2u);
}

// 100 agents on random-32-32-20 (MR23-I-04, RANDOM-01), a few hundred steps, every step
// validated: no solver may ever make an invalid move.
class LorrRuns : public ::testing::TestWithParam<std::string> {};

TEST_P(LorrRuns, RoundRobin2023ValidatorClean)
{
  ttest::Lorr L("/2023/random.domain/MR23-I-04.json");
  RoundRobin rr(L.file);
  LifelongOptions opt;
  opt.steps = 300;
  opt.budget = planner::Budget{50.0, 100};
  const LifelongResult r = run_lifelong(L.g, L.starts, rr, GetParam(), 0, opt);
  EXPECT_EQ(r.planner_errors, 0) << r.first_error;
  EXPECT_EQ(r.steps, 300);
  EXPECT_EQ(r.errands_finished, static_cast<long>(r.events.size()));
  EXPECT_EQ(r.tasks_finished, r.errands_finished);  // one-errand tasks
  EXPECT_GT(r.errands_finished, 300);               // > 1 per step with 100 agents
  for (size_t k = 1; k < r.events.size(); ++k) EXPECT_LE(r.events[k - 1].t, r.events[k].t);
}

TEST_P(LorrRuns, Pool2024ValidatorClean)
{
  ttest::Lorr L("/2024/random.domain/RANDOM-01.json");
  for (const std::string assigner : {"greedy", "hungarian"})
    for (bool reassign : {false, true}) {
      SCOPED_TRACE(assigner + (reassign ? " reassign" : " keep"));
      TaskPool pool(L.file, L.g, L.p.pool_size(), make_assigner(assigner), reassign);
      LifelongOptions opt;
      opt.steps = 200;
      opt.budget = planner::Budget{50.0, 100};
      const LifelongResult r = run_lifelong(L.g, L.starts, pool, GetParam(), 0, opt);
      EXPECT_EQ(r.planner_errors, 0) << r.first_error;
      EXPECT_GT(r.tasks_finished, 50);
      EXPECT_GT(r.errands_finished, r.tasks_finished);  // 2..5 errands per task
      EXPECT_EQ(pool.reassignments() > 0, reassign);
      // An opened task never changes agent: all errands of a task, in order, by one agent.
      std::map<long, std::pair<int, int>> by_task;  // task -> (agent, next errand)
      for (const Event& e : r.events) {
        auto& [agent, next] = by_task.emplace(e.task, std::make_pair(e.agent, 0)).first->second;
        EXPECT_EQ(agent, e.agent) << "task " << e.task << " changed agent after it opened";
        EXPECT_EQ(next, e.errand) << "task " << e.task;
        next = e.errand + 1;
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Solvers, LorrRuns, ::testing::Values("pibt", "naive", "rtlacam"));

TEST(Lifelong, DuplicateGoalsAreFine)
{
  // Four agents, every task at one of two stations: goals coincide all the time.
  const auto g = ttest::grid({".....", ".@.@.", "....."});
  auto file = ttest::task_file(g, {{{0, 0}}, {{4, 2}}, {{0, 0}}, {{4, 2}}, {{4, 2}}, {{0, 0}}, {{4, 2}}, {{0, 0}}});
  for (const std::string solver : {"pibt", "naive", "rtlacam"}) {
    RoundRobin rr(file);
    LifelongOptions opt;
    opt.steps = 200;
    opt.budget = planner::Budget{50.0, 500};
    const Config starts{g.at(2, 0), g.at(2, 2), g.at(1, 0), g.at(3, 2)};
    const LifelongResult r = run_lifelong(g, starts, rr, solver, 0, opt);
    EXPECT_EQ(r.planner_errors, 0) << solver << ": " << r.first_error;
    if (solver == "rtlacam") {
      EXPECT_GT(r.errands_finished, 10) << solver;
    }
  }
}

// Three agents in a corridor with one siding; the middle one is parked on its own station
// while the outer two shuttle between the two ends (the planner tests' "parked_in_corridor"
// made lifelong). PIBT alone finishes a couple of errands and then stalls for good;
// RT-LaCAM with progress epochs keeps finishing errands to the end.
TEST(Lifelong, ThroughputNeverStaysAtZeroWhereProgressIsPossible)
{
  const auto g = ttest::grid({"........", "@@@@.@@@"});
  // Lines 0..2: the agents' first errands (ends swapped, the middle stays); lines 3..5:
  // back to the starts. Round robin with 3 agents alternates the two forever.
  auto file = ttest::task_file(g, {{{7, 0}}, {{3, 0}}, {{0, 0}}, {{0, 0}}, {{3, 0}}, {{7, 0}}});
  const Config starts{g.at(0, 0), g.at(3, 0), g.at(7, 0)};
  LifelongOptions opt;
  opt.steps = 400;
  opt.budget = planner::Budget{50.0, 100};  // expansions run out first: deterministic

  RoundRobin rr(file);
  const LifelongResult rt = run_lifelong(g, starts, rr, "rtlacam", 0, opt);
  EXPECT_EQ(rt.planner_errors, 0) << rt.first_error;
  EXPECT_GE(rt.errands_finished, 100);
  EXPECT_LE(longest_drought(rt), 40);

  RoundRobin rr2(file);
  const LifelongResult pibt = run_lifelong(g, starts, rr2, "pibt", 0, opt);
  EXPECT_EQ(pibt.planner_errors, 0) << pibt.first_error;
  EXPECT_LE(pibt.errands_finished, 10);
  EXPECT_GE(longest_drought(pibt), 300) << "PIBT was expected to stall here";
}
