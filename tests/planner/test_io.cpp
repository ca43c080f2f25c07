// MovingAI readers and instance checks: good files load, bad ones give one clear error
// naming file and line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "planner/error.hpp"
#include "planner/movingai.hpp"
#include "planner/plan_io.hpp"
#include "address_cap.hpp"
#include "temp_path.hpp"

using namespace planner;

namespace {

std::string write_tmp(const std::string& name, const std::string& text)
{
  return test::temp_file(name, text);
}

const char* kMap = "type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n";

std::string scen_line(int sx, int sy, int gx, int gy) {
  return "0\tm.map\t4\t3\t" + std::to_string(sx) + "\t" + std::to_string(sy) + "\t" + std::to_string(gx) + "\t" +
         std::to_string(gy) + "\t1\n";
}

// Expects InputError whose message contains every fragment.
template <class F>
void expect_error(F f, std::vector<std::string> fragments)
{
  try {
    f();
    FAIL() << "no error";
  } catch (const InputError& e) {
    std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    for (auto& s : fragments) EXPECT_NE(m.find(s), std::string::npos) << "'" << s << "' not in: " << m;
  }
}

// read_plan's error for `text` as plan file p.txt on `g` ("no error" when it reads).
std::string plan_error(const Graph& g, const std::string& text)
{
  std::stringstream in(text);
  try {
    read_plan(in, g, "p.txt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(MovingAi, LoadsTheBenchmarkMap)
{
  Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  EXPECT_EQ(g.width(), 32);
  EXPECT_EQ(g.height(), 32);
  EXPECT_EQ(g.size(), 819);
  int comps = 0;
  g.components(&comps);
  EXPECT_EQ(comps, 1);
  for (Vertex v = 0; v < g.size(); ++v)
    for (Vertex u : g.neighbors(v)) {
      EXPECT_TRUE(g.adjacent(u, v));
      EXPECT_EQ(std::abs(g.cell_x(u) - g.cell_x(v)) + std::abs(g.cell_y(u) - g.cell_y(v)), 1);
    }
  Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 409);
  EXPECT_EQ(ins.num_agents(), 409);
  EXPECT_EQ(ins.source_lines.front(), 2);
}

TEST(MovingAi, SmallMapStructure)
{
  Graph g = load_map(write_tmp("small.map", kMap));
  EXPECT_EQ(g.size(), 10);
  EXPECT_EQ(g.num_edges(), 10u);
  EXPECT_EQ(g.at(1, 1), -1);
  EXPECT_EQ(g.degree(g.at(0, 0)), 2);
  EXPECT_EQ(g.degree(g.at(1, 0)), 2);
}

// A UTF-8 byte order mark before the header is skipped (it failed the header check as if
// the first line said something else).
TEST(MovingAi, ByteOrderMarkIsSkipped)
{
  const std::string bom = "\xEF\xBB\xBF";
  Graph g = load_map(write_tmp("bom.map", bom + kMap));
  EXPECT_EQ(g.size(), 10);
  const Instance ins = load_scen(write_tmp("bom.scen", bom + "version 1\n" + scen_line(0, 0, 3, 2)), g, 1);
  EXPECT_EQ(ins.starts, Config{g.at(0, 0)});
  std::stringstream plan(bom + "solution=\n0:(0,0),\n");
  EXPECT_EQ(read_plan(plan, g, "p.txt"), std::vector<Config>{Config{g.at(0, 0)}});
}

TEST(MovingAi, MapErrorsNameFileAndLine)
{
  expect_error([] { load_map("/nonexistent/x.map"); }, {"/nonexistent/x.map", "cannot open"});
  expect_error([] { load_map(write_tmp("a.map", "hello\n")); }, {"a.map:1", "type octile"});
  expect_error([] { load_map(write_tmp("b.map", "type octile\nheight x\nwidth 4\nmap\n")); }, {"b.map:2", "height"});
  expect_error([] { load_map(write_tmp("c.map", "type octile\nheight 3\nwidth 4\nmap\n....\n.@@\n....\n")); },
               {"c.map:6", "3 characters"});
  expect_error([] { load_map(write_tmp("d.map", "type octile\nheight 3\nwidth 4\nmap\n....\n.@#.\n....\n")); },
               {"d.map:6", "'#'"});
  expect_error([] { load_map(write_tmp("e.map", "type octile\nheight 3\nwidth 4\nmap\n....\n")); }, {"e.map:", "ends after 1"});
}

// A 45-byte map claiming 100000 x 100000 cells used to allocate and zero 1.25 GB before
// finding no rows. More cells than an int indexes are refused from the header; a smaller
// claim costs memory only for the rows the file has. The second half runs in a child whose
// address space may grow by 128 MiB only: sizing 46000 x 46000 flags (265 MB) from the
// header throws std::bad_alloc there (Linux overcommit would hide it otherwise).
TEST(MovingAi, HugeHeaderIsNotAllocated)
{
  const std::string head = "type octile\nheight 100000\nwidth 100000\nmap\n";
  expect_error([&] { load_map(write_tmp("huge.map", head)); }, {"huge.map:4", "100000 x 100000 cells is too large"});
  RTLACAM_SKIP_UNDER_ASAN();
  const std::string big = write_tmp("big.map", "type octile\nheight 46000\nwidth 46000\nmap\n");
  auto load_capped = [&] { test::exit_after_capped(test::address_space_now() + (128ul << 20), [&] { load_map(big); }); };
  EXPECT_EXIT(load_capped(), testing::ExitedWithCode(0), "big.map:5: map ends after 0 of 46000 rows");
}

TEST(MovingAi, ScenErrorsNameFileAndLine)
{
  Graph g = load_map(write_tmp("m.map", kMap));
  auto scen = [](const std::string& name, const std::string& body) { return write_tmp(name, "version 1\n" + body); };
  expect_error([&] { load_scen("/nonexistent/x.scen", g, 1); }, {"x.scen", "cannot open"});
  expect_error([&] { load_scen(scen("n.scen", scen_line(0, 0, 3, 0)), g, 2); }, {"n.scen", "asked for 2", "only 1"});
  expect_error([&] { load_scen(scen("o.scen", scen_line(0, 0, 3, 0) + scen_line(1, 1, 3, 2)), g, 2); },
               {"o.scen:3", "start (1,1)", "obstacle"});
  expect_error([&] { load_scen(scen("f.scen", scen_line(0, 0, 9, 0)), g, 1); }, {"f.scen:2", "goal (9,0)", "off the map"});
  expect_error([&] { load_scen(scen("d.scen", scen_line(0, 0, 3, 0) + scen_line(0, 0, 3, 2)), g, 2); },
               {"d.scen:3", "agent 1", "duplicate start"});
  expect_error([&] { load_scen(scen("g.scen", scen_line(0, 0, 3, 0) + scen_line(0, 2, 3, 0)), g, 2); },
               {"g.scen:3", "duplicate goal"});
  expect_error([&] { load_scen(scen("m.scen", "0\tm.map\t4\t3\t0\t0\n"), g, 1); }, {"m.scen:2", "expected"});
  expect_error([&] { load_scen(write_tmp("v.scen", "hello\n"), g, 1); }, {"v.scen:1", "version 1"});
  expect_error([&] { load_scen(scen("w.scen", "0\tm.map\t5\t3\t0\t0\t1\t0\t1\n"), g, 1); }, {"w.scen:2", "5x3"});
}

TEST(MovingAi, UnreachableGoalIsAnError)
{
  Graph g = load_map(write_tmp("split.map", "type octile\nheight 1\nwidth 5\nmap\n..@..\n"));
  std::string s = write_tmp("split.scen", "version 1\n0\tsplit.map\t5\t1\t0\t0\t4\t0\t4\n");
  expect_error([&] { load_scen(s, g, 1); }, {"split.scen:2", "unreachable"});
}

TEST(Graph, AttachGridChecksTheLattice)
{
  // A 3-vertex path laid out as an L on a 2x2 grid.
  Graph g = Graph::from_edges(3, {{0, 1}, {1, 2}});
  Graph h = g;
  h.attach_grid(2, 2, {0, 1, 3});  // (0,0) - (1,0) - (1,1)
  EXPECT_TRUE(h.is_grid());
  EXPECT_EQ(h.at(1, 1), 2);
  EXPECT_EQ(h.at(0, 1), -1);
  EXPECT_EQ(h.cell_x(2), 1);
  Graph a = g, b = g, c = g;
  EXPECT_THROW(a.attach_grid(2, 2, {0, 1, 2}), std::invalid_argument);  // (1,0)-(0,1) not neighbours
  EXPECT_THROW(b.attach_grid(2, 2, {0, 1, 1}), std::invalid_argument);  // shared cell
  EXPECT_THROW(c.attach_grid(2, 2, {0, 1}), std::invalid_argument);     // one cell per vertex
}

TEST(PlanIo, ReadsBackWhatItWritesAndNamesBadLines)
{
  const Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  const Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 3);
  std::vector<Config> plan = {ins.starts, ins.starts};
  std::stringstream s;
  write_plan(s, g, ins.starts, ins.goals, plan, PlanHeader{});
  EXPECT_EQ(read_plan(s, g, "p.txt"), plan);
  auto error_of = [&](const std::string& text) { return plan_error(g, text); };
  EXPECT_EQ(error_of("agents=1\n"), "p.txt: no 'solution=' line");
  EXPECT_EQ(error_of("solution=\n1:(0,0),\n"), "p.txt:2: timestep '1', expected 0");
  EXPECT_EQ(error_of("solution=\n0:(99,99),\n"), "p.txt:2: cell (99,99) is off the map");
  EXPECT_EQ(error_of("solution=\n0 (1,1)\n"), "p.txt:2: expected 't:(x,y),...'");
}

// A coordinate beyond int is an error naming its line: sscanf's %d wrapped 4294967299 to 3,
// so rtlacam-check took a jump off the map for a move to (3,0) and called the plan valid.
// CRLF plans read as LF ones (the map and scen readers strip '\r' too).
TEST(PlanIo, CoordinatesBeyondIntAreErrorsAndCrlfReads)
{
  const Graph g = load_map(RTLACAM_TEST_DATA "/planner/random-32-32-20.map");
  auto error_of = [&](const std::string& text) { return plan_error(g, text); };
  EXPECT_EQ(error_of("solution=\n0:(0,0),\n1:(4294967296,0),\n"),
            "p.txt:3: expected '(x,y)' with integer coordinates, not '(4294967296,0)'");
  EXPECT_EQ(error_of("solution=\n0:(0,-9999999999),\n"),
            "p.txt:2: expected '(x,y)' with integer coordinates, not '(0,-9999999999)'");
  EXPECT_EQ(error_of("solution=\n0:(a,0),\n"), "p.txt:2: expected '(x,y)' with integer coordinates, not '(a,0)'");
  const Instance ins = load_scen(RTLACAM_TEST_DATA "/planner/random-32-32-20-random-1.scen", g, 3);
  const std::vector<Config> plan = {ins.starts, ins.starts};
  std::stringstream lf;
  write_plan(lf, g, ins.starts, ins.goals, plan, PlanHeader{});
  std::string crlf;
  for (char c : lf.str() + "\n") crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);  // and a blank line
  std::stringstream in(crlf);
  EXPECT_EQ(read_plan(in, g, "p.txt"), plan);
}
