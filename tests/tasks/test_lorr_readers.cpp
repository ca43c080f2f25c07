// LoRR readers: the real 2023/2024 files load; broken files fail with one clear line
// naming file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "planner/error.hpp"
#include "planner/movingai.hpp"
#include "tasks/lorr_files.hpp"
#include "tasks/lorr_instance.hpp"
#include "tasks/lorr_problem.hpp"
#include "tasks_test_util.hpp"

using namespace tasks;

namespace {

const std::string kMap2023 = ttest::kData + "/2023/random.domain/maps/random-32-32-20.map";

// Runs f, expects an InputError whose message contains every `parts`, on one line.
template <class F>
void expect_error(F f, const std::vector<std::string>& parts)
{
  try {
    f();
    FAIL() << "no error";
  } catch (const planner::InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    for (const auto& p : parts) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' not in: " << m;
  }
}

}  // namespace

TEST(LorrProblem, Reads2023)
{
  const LorrProblem p = load_lorr_problem(ttest::kData + "/2023/random.domain/MR23-I-04.json");
  EXPECT_EQ(p.name, "MR23-I-04");
  EXPECT_EQ(p.team_size, 100);
  EXPECT_EQ(p.year, 2023);
  EXPECT_EQ(p.strategy, "roundrobin");
  EXPECT_EQ(p.default_mode(), "roundrobin");
  EXPECT_EQ(p.simulation_time, 500);
  EXPECT_EQ(p.map_file, ttest::kData + "/2023/random.domain/maps/random-32-32-20.map");
  EXPECT_EQ(p.pool_size(), 100);
}

TEST(LorrProblem, Reads2024)
{
  const LorrProblem p = load_lorr_problem(ttest::kData + "/2024/random.domain/RANDOM-01.json");
  EXPECT_EQ(p.year, 2024);
  EXPECT_EQ(p.default_mode(), "pool");
  EXPECT_DOUBLE_EQ(p.num_tasks_reveal, 1.5);
  EXPECT_EQ(p.pool_size(), 150);
  EXPECT_EQ(p.simulation_time, 600);
}

TEST(LorrProblem, Errors)
{
  expect_error([] { load_lorr_problem("/nonexistent/p.json"); }, {"/nonexistent/p.json", "cannot open"});
  const std::string bad = ttest::temp_file("bad.json", "{ \"mapFile\": ");
  expect_error([&] { load_lorr_problem(bad); }, {bad, "invalid JSON"});
  const std::string nomap = ttest::temp_file("nomap.json", R"({"agentFile":"a","taskFile":"t","teamSize":3})");
  expect_error([&] { load_lorr_problem(nomap); }, {nomap, "mapFile"});
  const std::string team = ttest::temp_file("team.json", R"({"mapFile":"m","agentFile":"a","taskFile":"t","teamSize":-2})");
  expect_error([&] { load_lorr_problem(team); }, {team, "teamSize"});
}

// Found by libFuzzer: inputs the JSON parser or pool_size() could not represent.
const std::string kProblemHead = R"({"mapFile":"m","agentFile":"a","taskFile":"t","teamSize":100,)";

// nlohmann throws out_of_range, not parse_error, on 1e400: it escaped without the file name.
TEST(LorrProblem, NumberOverflowNamesTheFile)
{
  const std::string p = test::temp_file("huge_number.json", kProblemHead + R"("numTasksReveal":1e400})");
  expect_error([&] { load_lorr_problem(p); }, {p + ": invalid JSON: ", "number overflow parsing '1e400'"});
}

// 4.3e10 x 100 tasks: undefined behaviour converting to int (pool_size() returned teamSize).
TEST(LorrProblem, HugeNumTasksRevealIsAnError)
{
  const std::string p = test::temp_file("reveal.json", kProblemHead + R"("numTasksReveal":42949672961.5})");
  expect_error([&] { load_lorr_problem(p); }, {p + ": field 'numTasksReveal' x teamSize must be at most 10000000 tasks"});
}

// A simulation_time.json that is not an object threw json::invalid_iterator from key().
TEST(LorrProblem, SimulationTimeMustBeAnObject)
{
  const std::string dir = test::temp_dir("lorr_simtime");
  std::ofstream(dir + "/simulation_time.json") << "[600]";
  const std::string p = test::temp_file("lorr_simtime/RANDOM-01.json", kProblemHead + R"("numTasksReveal":1.5})");
  expect_error([&] { load_lorr_problem(p); }, {dir + "/simulation_time.json: expected a JSON object of instance name -> steps"});
}

// A key given twice in one object is an error naming it (nlohmann kept the last one
// silently: a second "mapFile" replaced the first); the same key in two objects is fine.
TEST(LorrProblem, DuplicateKeysAreAnError)
{
  const std::string p = test::temp_file("dupkey.json", kProblemHead + R"("numTasksReveal":1.5,"mapFile":"x"})");
  expect_error([&] { load_lorr_problem(p); }, {p + ": key 'mapFile' appears twice in one object"});
  const std::string ok = test::temp_file("nested.json", kProblemHead + R"("extra":{"mapFile":1,"a":{"mapFile":2}}})");
  EXPECT_EQ(load_lorr_problem(ok).team_size, 100);
}

// A UTF-8 byte order mark before an agents file's count is skipped, as in .map / .scen.
TEST(LorrFiles, ByteOrderMarkIsSkipped)
{
  const planner::Graph g = planner::load_map(kMap2023);
  const std::string p = test::temp_file("bom.agents", "\xEF\xBB\xBF" "1\n516\n");
  EXPECT_EQ(load_lorr_agents(p, g), planner::Config{g.at(516 % 32, 516 / 32)});
}

TEST(LorrFiles, ReadsAgentsAndTasks)
{
  const planner::Graph g = planner::load_map(kMap2023);
  const planner::Config s = load_lorr_agents(ttest::kData + "/2023/random.domain/agents/random-32-32-20_100.agents", g, 100);
  ASSERT_EQ(s.size(), 100u);
  EXPECT_EQ(s[0], g.at(516 % 32, 516 / 32));  // first id of the file
  const TaskFile t = load_lorr_tasks(ttest::kData + "/2023/random.domain/tasks/random-32-32-20_100.tasks", g);
  EXPECT_EQ(t.size(), 2000);
  EXPECT_EQ(t.tasks[0], std::vector<planner::Vertex>{g.at(81 % 32, 81 / 32)});
  EXPECT_EQ(t.lines[0], 2);

  const planner::Graph g24 = planner::load_map(ttest::kData + "/2024/random.domain/maps/random-32-32-20.map");
  const TaskFile t24 = load_lorr_tasks(ttest::kData + "/2024/random.domain/tasks/random_32_32_20.tasks", g24);
  EXPECT_EQ(t24.size(), 1000);
  EXPECT_EQ(t24.lines[0], 3);  // after the '#' comment and the count
  const std::vector<planner::Vertex> first{g24.at(566 % 32, 566 / 32), g24.at(822 % 32, 822 / 32),
                                           g24.at(422 % 32, 422 / 32), g24.at(356 % 32, 356 / 32)};
  EXPECT_EQ(t24.tasks[0], first);
  const planner::Config s24 = load_lorr_agents(ttest::kData + "/2024/random.domain/agents/random_32_32_20_100.agents", g24);
  EXPECT_EQ(s24.size(), 100u);
}

TEST(LorrFiles, Errors)
{
  // 3 x 2 map, (1, 0) blocked: ids 0..5, id 1 an obstacle.
  const std::string map = ttest::temp_file("t.map", "type octile\nheight 2\nwidth 3\nmap\n.@.\n...\n");
  const planner::Graph g = planner::load_map(map);

  const std::string short_agents = ttest::temp_file("short.agents", "# c\n3\n0\n2\n");
  expect_error([&] { load_lorr_agents(short_agents, g); }, {short_agents + ":4", "declares 3 agents but has only 2"});
  const std::string team = ttest::temp_file("team.agents", "2\n0\n2\n");
  expect_error([&] { load_lorr_agents(team, g, 5); }, {team + ":1", "teamSize 5", "only 2"});
  const std::string off = ttest::temp_file("off.agents", "2\n0\n6\n");
  expect_error([&] { load_lorr_agents(off, g); }, {off + ":3", "cell id 6 is off the map"});
  const std::string neg = ttest::temp_file("neg.agents", "1\n-1\n");
  expect_error([&] { load_lorr_agents(neg, g); }, {neg + ":2", "off the map"});
  const std::string obst = ttest::temp_file("obst.agents", "2\n0\n1\n");
  expect_error([&] { load_lorr_agents(obst, g); }, {obst + ":3", "cell id 1 (row 0, column 1) is an obstacle"});
  const std::string dup = ttest::temp_file("dup.agents", "2\n3\n3\n");
  expect_error([&] { load_lorr_agents(dup, g); }, {dup + ":3", "already the start"});
  const std::string word = ttest::temp_file("word.agents", "x\n");
  expect_error([&] { load_lorr_agents(word, g); }, {word + ":1", "number of agents"});
  const std::string empty = ttest::temp_file("empty.agents", "# only a comment\n");
  expect_error([&] { load_lorr_agents(empty, g); }, {empty + ":2", "end of file"});

  const std::string short_tasks = ttest::temp_file("short.tasks", "5\n0,2\n3\n");
  expect_error([&] { load_lorr_tasks(short_tasks, g); }, {short_tasks + ":3", "declares 5 tasks but has only 2"});
  const std::string bad_field = ttest::temp_file("bad.tasks", "2\n0,2\n3,,4\n");
  expect_error([&] { load_lorr_tasks(bad_field, g); }, {bad_field + ":3", "comma-separated"});
  const std::string obst_task = ttest::temp_file("obst.tasks", "1\n0,1\n");
  expect_error([&] { load_lorr_tasks(obst_task, g); }, {obst_task + ":2", "obstacle"});
  const std::string off_task = ttest::temp_file("off.tasks", "1\n99\n");
  expect_error([&] { load_lorr_tasks(off_task, g); }, {off_task + ":2", "off the map"});
  const std::string none = ttest::temp_file("none.tasks", "0\n");
  expect_error([&] { load_lorr_tasks(none, g); }, {none + ":1", "no tasks"});

  // Extra lines after the declared count are ignored (as the start kits do); CRLF is fine.
  const std::string crlf = ttest::temp_file("crlf.tasks", "1\r\n2,3\r\n4\r\n");
  EXPECT_EQ(load_lorr_tasks(crlf, g).size(), 1);
}

TEST(LorrInstance, LoadsEverythingTheProblemNamesAndTakesAPrefixOfTheTeam)
{
  const std::string p = ttest::kData + "/2023/random.domain/MR23-I-04.json";
  const LorrInstance in = load_lorr_instance(p);
  EXPECT_EQ(in.problem.team_size, 100);
  EXPECT_EQ(in.g.size(), planner::load_map(kMap2023).size());
  ASSERT_EQ(in.starts.size(), 100u);
  EXPECT_EQ(in.starts[0], in.g.at(516 % 32, 516 / 32));
  ASSERT_TRUE(in.tasks);
  EXPECT_EQ(in.tasks->size(), 2000);
  const LorrInstance some = load_lorr_instance(p, 30);
  EXPECT_EQ(some.problem.team_size, 30);
  ASSERT_EQ(some.starts.size(), 30u);
  EXPECT_TRUE(std::equal(some.starts.begin(), some.starts.end(), in.starts.begin()));
  expect_error([&] { load_lorr_instance(p, 101, "agents="); }, {p + ": ", "agents=101 but teamSize is 100"});
}
