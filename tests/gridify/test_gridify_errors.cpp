// Bad inputs: each gives one clear line naming the file (and line / edge), never a crash;
// the options that turn some of them into reported drops.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <typeinfo>

#include "gridify/gridifier.hpp"
#include "gridify/movingai_map.hpp"
#include "gridify_test_util.hpp"
#include "planner/error.hpp"
#include "temp_path.hpp"

using namespace gridify;
using namespace gridify_test;

namespace {

// The message of the InputError gridify throws (fails the test if none is thrown).
std::string error_of(const std::string& net, GridifyOptions opt = {})
{
  try {
    gridify::gridify(net, opt);
  } catch (const planner::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << net;
  return "";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Junctions j0, j1, ... at x = xs[k] (y = 0), consecutive ones joined by an aisle whose two
// lanes are `len` long, with U-turn connections at both ends of every aisle.
std::string line_net(const std::vector<std::string>& xs, const std::string& len)
{
  std::string t = "<net version=\"1.9\">\n";
  auto j = [](size_t k) { return "j" + std::to_string(k); };
  for (size_t k = 0; k < xs.size(); ++k)
    t += "  <junction id=\"" + j(k) + "\" type=\"unregulated\" x=\"" + xs[k] + "\" y=\"0\"/>\n";
  for (size_t k = 0; k + 1 < xs.size(); ++k)
    for (const auto& [from, to] : {std::make_pair(j(k), j(k + 1)), std::make_pair(j(k + 1), j(k))}) {
      t += "  <edge id=\"" + from + "_" + to + "\" from=\"" + from + "\" to=\"" + to + "\">\n";
      t += "    <lane id=\"" + from + "_" + to + "_0\" index=\"0\" length=\"" + len + "\"/>\n  </edge>\n";
      t += "  <connection from=\"" + from + "_" + to + "\" to=\"" + to + "_" + from + "\" fromLane=\"0\" toLane=\"0\" dir=\"t\"/>\n";
    }
  return t + "</net>\n";
}

}  // namespace

// A one-way aisle into a dead end (b -> d, nothing leaves d) is kept as arcs, but its
// cells cannot get back: they are dropped with the cells outside the largest strongly
// connected component, or, asked to keep everything, the net is refused naming them.
TEST(GridifyErrors, OneWayDeadEndIsNotStronglyConnected)
{
  NetFile net = NetFile::read(data("oneway.net.xml"));
  CellMap m = gridify::gridify(net);
  EXPECT_EQ(m.aisles.size(), 2u);
  EXPECT_EQ(m.junction_cell("d"), -1);
  EXPECT_FALSE(m.graph.directed());  // what is left is two-way
  bool b_d_dropped = false;
  for (const Dropped& d : m.dropped)
    for (const std::string& id : d.members) b_d_dropped |= d.kind == "component" && id == "b_d";
  EXPECT_TRUE(b_d_dropped);
  expect_invariants(m, net);
  GridifyOptions opt;
  opt.keep_largest = false;
  std::string e = error_of(data("oneway.net.xml"), opt);
  EXPECT_TRUE(has(e, "oneway.net.xml:")) << e;
  EXPECT_TRUE(has(e, "not strongly connected")) << e;
}

// One-way rows joined by two-way cross aisles: the one-way aisles become arcs A->B only.
// Fails if gridify made them two-way (or refused them, as it did before).
TEST(GridifyErrors, OneWayAislesBecomeDirectedArcs)
{
  NetFile net = NetFile::read(data("oneway_loop.net.xml"));
  CellMap m = gridify::gridify(net);
  expect_invariants(m, net);
  EXPECT_TRUE(m.dropped.empty());
  ASSERT_EQ(m.aisles.size(), 7u);
  EXPECT_TRUE(m.graph.directed());
  EXPECT_EQ(m.graph.num_one_way(), 4u * 3u);  // 4 one-way aisles of 3 steps
  int one_way = 0;
  for (const Aisle& a : m.aisles) {
    if (!a.one_way) continue;
    ++one_way;
    EXPECT_EQ(a.ba, "");
    for (size_t k = 0; k + 1 < a.cells.size(); ++k) {
      EXPECT_TRUE(m.graph.adjacent(a.cells[k], a.cells[k + 1])) << a.ab;
      EXPECT_FALSE(m.graph.adjacent(a.cells[k + 1], a.cells[k])) << a.ab;
      EXPECT_EQ(m.pose_entering(a.cells[k], a.cells[k + 1]).lane, a.lane_ab);
      EXPECT_THROW(m.pose_entering(a.cells[k + 1], a.cells[k]), std::invalid_argument);
    }
  }
  EXPECT_EQ(one_way, 4);
  // With --drop-one-way the rows go and the cross aisles fall apart into pieces.
  GridifyOptions opt;
  opt.drop_one_way = true;
  EXPECT_EQ(gridify::gridify(net, opt).aisles.size(), 1u);
}

TEST(GridifyErrors, OneWayAisleDroppedOnRequest)
{
  GridifyOptions opt;
  opt.drop_one_way = true;
  NetFile net = NetFile::read(data("oneway.net.xml"));
  CellMap m = gridify::gridify(net, opt);
  EXPECT_EQ(m.aisles.size(), 2u);
  EXPECT_EQ(m.cells.size(), 3u + 4u);  // a, b, c + 2 cells per 3 m aisle
  EXPECT_EQ(m.junction_cell("d"), -1);
  ASSERT_EQ(m.dropped.size(), 2u);
  EXPECT_EQ(m.dropped[0].kind, "one-way edge");
  EXPECT_EQ(m.dropped[0].id, "b_d");
  EXPECT_EQ(m.dropped[1].kind, "component");  // d is left without aisles
  EXPECT_EQ(m.dropped[1].id, "d");
  expect_invariants(m, net);
}

TEST(GridifyErrors, LengthNotAMultipleOfTheCell)
{
  std::string e = error_of(data("notmultiple.net.xml"));
  EXPECT_TRUE(has(e, "notmultiple.net.xml:")) << e;
  EXPECT_TRUE(has(e, "edge 'b_c': length 3.4 is not a multiple of cell_length 1 (use --snap)")) << e;
  GridifyOptions opt;
  opt.cell_length = 5;
  e = error_of(data("notmultiple.net.xml"), opt);
  EXPECT_TRUE(has(e, "length 3 is shorter than cell_length 5")) << e;
}

TEST(GridifyErrors, LengthSnappedOnRequest)
{
  GridifyOptions opt;
  opt.snap = true;
  NetFile net = NetFile::read(data("notmultiple.net.xml"));
  CellMap m = gridify::gridify(net, opt);
  ASSERT_EQ(m.aisles.size(), 2u);
  const Aisle& bc = m.aisles[1];
  EXPECT_EQ(bc.ab, "b_c");
  EXPECT_TRUE(bc.snapped);
  EXPECT_EQ(bc.steps, 3);
  EXPECT_NEAR(bc.spacing, 3.4 / 3, 1e-12);
  const Cell& last = m.cells[bc.cells[2]];  // k = 2
  EXPECT_NEAR(last.poses[0].pos, 2 * 3.4 / 3, 1e-12);
  EXPECT_NEAR(last.poses[1].pos, 3.4 - 2 * 3.4 / 3, 1e-12);
  EXPECT_FALSE(m.aisles[0].snapped);
  EXPECT_EQ(m.warnings.size(), 1u);
  expect_invariants(m, net);
  // Within the tolerance a length counts as a multiple.
  GridifyOptions loose;
  loose.tolerance = 0.5;
  EXPECT_EQ(gridify::gridify(net, loose).aisles[1].steps, 3);
}

TEST(GridifyErrors, DisconnectedNetKeepsTheLargestComponent)
{
  NetFile net = NetFile::read(data("disconnected.net.xml"));
  CellMap m = gridify::gridify(net);
  EXPECT_EQ(m.num_junction_cells(), 4);  // a b c d
  EXPECT_EQ(m.aisles.size(), 3u);
  EXPECT_EQ(m.cells.size(), 4u + 3u);    // 2 m aisles: 1 cell each
  EXPECT_EQ(m.junction_cell("e"), -1);
  ASSERT_EQ(m.dropped.size(), 1u);
  EXPECT_EQ(m.dropped[0].kind, "component");
  EXPECT_EQ(m.dropped[0].id, "e, f");
  EXPECT_TRUE(has(m.dropped[0].reason, "4 cell(s)")) << m.dropped[0].reason;
  EXPECT_EQ(m.dropped[0].segments.size(), 1u + 2u);  // aisle e-f, junctions e and f
  expect_invariants(m, net);
  // Lanes of the dropped part are not located.
  EXPECT_EQ(m.locate("e_f_0", 1.0), -1);

  GridifyOptions strict;
  strict.keep_largest = false;
  std::string e = error_of(data("disconnected.net.xml"), strict);
  EXPECT_TRUE(has(e, "disconnected")) << e;
}

TEST(GridifyErrors, InternalLinksAreRefusedClearly)
{
  std::string e = error_of(data("internal.net.xml"));
  EXPECT_TRUE(has(e, "internal.net.xml")) << e;
  EXPECT_TRUE(has(e, "--no-internal-links")) << e;
}

TEST(GridifyErrors, MissingFile)
{
  std::string e = error_of(data("no_such_file.net.xml"));
  EXPECT_TRUE(has(e, "no_such_file.net.xml: cannot open file")) << e;
}

TEST(GridifyErrors, MalformedXmlNamesFileAndLine)
{
  EXPECT_TRUE(has(error_of(data("malformed.net.xml")), "malformed.net.xml:7: malformed XML"));
  EXPECT_TRUE(has(error_of(data("empty.net.xml")), "empty.net.xml:1: malformed XML"));
  EXPECT_TRUE(has(error_of(data("not_a_net.xml")), "no <net> root element"));
}

TEST(GridifyErrors, MissingOrBadAttributes)
{
  EXPECT_EQ(error_of(data("missing_length.net.xml")),
            data("missing_length.net.xml") + ":9: <lane id='b_a_0'>: missing attribute 'length'");
  EXPECT_EQ(error_of(data("nonnumeric.net.xml")),
            data("nonnumeric.net.xml") + ":12: <junction id='b'>: attribute 'x' is not a number: 'three'");
  EXPECT_EQ(error_of(data("unknown_junction.net.xml")),
            data("unknown_junction.net.xml") + ":5: edge 'a_b' refers to unknown junction 'zz'");
}

TEST(GridifyErrors, BadStationFiles)
{
  GridifyOptions opt;
  opt.additional = data("bad_station_lane.add.xml");
  std::string e = error_of(data("tiny.net.xml"), opt);
  EXPECT_TRUE(has(e, "bad_station_lane.add.xml:3: <busStop id='stopX'>: lane 'nowhere_0' is not in")) << e;
  opt.additional = data("bad_station_pos.add.xml");
  e = error_of(data("tiny.net.xml"), opt);
  EXPECT_TRUE(has(e, "bad_station_pos.add.xml:2:")) << e;
  EXPECT_TRUE(has(e, "'startPos' is not a number")) << e;
  opt.additional = data("no_such.add.xml");
  EXPECT_TRUE(has(error_of(data("tiny.net.xml"), opt), "no_such.add.xml: cannot open file"));
  // Two stations of one kind with one id: SUMO would stop at load with "Process Error".
  opt.additional = test::temp_file("dup.add.xml", "<additional>\n"
                                                  "    <busStop id=\"s\" lane=\"b_a_0\" startPos=\"0.5\" endPos=\"1\"/>\n"
                                                  "    <busStop id=\"s\" lane=\"a_b_0\" startPos=\"0.5\" endPos=\"1\"/>\n"
                                                  "</additional>\n");
  e = error_of(data("tiny.net.xml"), opt);
  EXPECT_TRUE(has(e, "dup.add.xml:3: <busStop id='s'>: duplicate id")) << e;
}

TEST(GridifyErrors, BadCellLength)
{
  GridifyOptions opt;
  opt.cell_length = 0;
  EXPECT_TRUE(has(error_of(data("tiny.net.xml"), opt), "cell_length must be a positive number"));
}

// The CLI prints the one-line error and exits 2 (bad input).
TEST(GridifyErrors, CliExitsNonZeroWithTheMessage)
{
  std::string log = temp_dir() + "/err.txt";
  std::string cmd = std::string(RTLACAM_GRIDIFY_CLI) + " '" + data("notmultiple.net.xml") + "' 2> '" + log + "' > /dev/null";
  int rc = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 2);
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_TRUE(has(ss.str(), "error: ")) << ss.str();
  EXPECT_TRUE(has(ss.str(), "notmultiple.net.xml:")) << ss.str();
  EXPECT_TRUE(has(ss.str(), "(use --snap)")) << ss.str();
  cmd = std::string(RTLACAM_GRIDIFY_CLI) + " '" + data("notmultiple.net.xml") + "' --snap -q";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
}

// Links need SUMO connections: without turnarounds a vehicle could drive into a dead end
// and never leave it (SUMO would end its trip), so dead-end junction cells are dropped and
// reported, and the missing U-turns elsewhere are counted.
TEST(GridifyErrors, LinksWithoutSumoConnectionsAreDropped)
{
  NetFile net = NetFile::read(data("noturnarounds.net.xml"));
  CellMap m = gridify::gridify(net);
  EXPECT_EQ(m.num_junction_cells(), 1);  // b
  EXPECT_EQ(m.num_aisle_cells(), 4);
  EXPECT_EQ(m.graph.num_edges(), 4u);
  int links = 0, comps = 0;
  for (const Dropped& d : m.dropped) links += d.kind == "link", comps += d.kind == "component";
  EXPECT_EQ(links, 2);
  EXPECT_EQ(comps, 2);
  ASSERT_EQ(m.warnings.size(), 2u);
  EXPECT_TRUE(has(m.warnings[0], "2 turn(s)")) << m.warnings[0];
  // Arriving cells next to a dead end still have both poses; b keeps its straight moves.
  EXPECT_EQ(m.cells[m.junction_cell("b")].movements.size(), 2u);
  expect_invariants(m, net);
}

// Robustness: every prefix of a real net and byte-level corruptions of it either gridify
// or fail with an InputError -- never another exception, never a crash.
TEST(GridifyErrors, TruncatedAndCorruptedNetsNeverCrash)
{
  std::ifstream in(scenario("small.net.xml"));
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const std::string dir = temp_dir();
  int ok = 0, input_errors = 0;
  auto attempt = [&](const std::string& content) {
    std::string path = dir + "/x.net.xml";
    std::ofstream(path) << content;
    try {
      gridify::gridify(path);
      ++ok;
    } catch (const planner::InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "multi-line message";
      ++input_errors;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "unexpected " << typeid(e).name() << ": " << e.what();
    }
  };
  for (size_t cut = 0; cut < text.size(); cut += 97) attempt(text.substr(0, cut));
  unsigned rng = 12345;
  const char junk[] = {'<', '>', '"', '=', '/', 'x', '0', '9', '-', ' ', '.', '\0'};
  for (int k = 0; k < 300; ++k) {
    std::string t = text;
    for (int j = 0; j < 3; ++j) {
      rng = rng * 1103515245u + 12345u;
      size_t at = (rng >> 8) % t.size();
      rng = rng * 1103515245u + 12345u;
      t[at] = junk[(rng >> 8) % sizeof(junk)];
    }
    attempt(t);
  }
  EXPECT_GT(input_errors, 0);
  EXPECT_GT(ok, 0);
}

// A 3e9 m lane used to become 3e9 steps cast to a negative int (a crash), a 1e9 m one a
// billion cells: more than kMaxCells cells is an error naming the edge.
TEST(GridifyErrors, HugeLaneLengthIsAnError)
{
  for (const std::string len : {"3e9", "1e9"}) {
    const std::string net = test::temp_file("huge_lane.net.xml", line_net({"0", "1"}, len));
    EXPECT_EQ(error_of(net), net + ":4: edge 'j0_j1': length " + (len == "3e9" ? "3e+09" : "1e+09") +
                                 " is more than 1000000 cells of cell_length 1");
  }
  // Two aisles of 600000 cells each: under the limit one by one, over it together.
  const std::string net = test::temp_file("two_long.net.xml", line_net({"0", "600000", "1200000"}, "600000"));
  EXPECT_EQ(error_of(net), net + ":13: the net has more than 1000000 cells of cell_length 1 (reached at edge 'j1_j2')");
}

// A junction 2^31 - 1 cell lengths from the other used to overflow the MovingAI lattice
// width (a crash); it is too large a lattice, so the net has no grid view.
TEST(GridifyErrors, FarApartJunctionsHaveNoGridView)
{
  const std::string net = test::temp_file("far.net.xml", line_net({"0", "2147483647"}, "1"));
  const CellMap m = gridify::gridify(net);
  EXPECT_EQ(m.cells.size(), 2u);
  EXPECT_FALSE(m.graph.is_grid());
  std::string why;
  EXPECT_EQ(grid_layout(m, &why).width, 0);
  EXPECT_EQ(why, "the lattice is too large");
}

// A lane whose allow / disallow shut out vehicle class passenger (the AGVs') is left out and
// said so ("closed edge"); kept, the AGVs were routed onto it and SUMO refused the route or
// the insertion mid-run. A net whose aisles are all closed to them (lane 0 a sidewalk) is
// refused naming the lane that does allow them.
TEST(GridifyErrors, LanesClosedToTheAgvsAreLeftOut)
{
  std::string t = line_net({"0", "2", "4"}, "2");
  auto close = [&](const std::string& lane, const std::string& attr) {
    const std::string from = "<lane id=\"" + lane + "\" ";
    const size_t at = t.find(from);
    ASSERT_NE(at, std::string::npos) << lane;
    t.insert(at + from.size(), attr + " ");
  };
  close("j1_j2_0", "allow=\"pedestrian bicycle\"");
  close("j2_j1_0", "disallow=\"passenger\"");
  CellMap m = gridify::gridify(test::temp_file("closed.net.xml", t));
  ASSERT_EQ(m.aisles.size(), 1u);
  EXPECT_EQ(m.aisles[0].ab, "j0_j1");
  int closed = 0;
  for (const Dropped& d : m.dropped)
    if (d.kind == "closed edge") {
      ++closed;
      EXPECT_TRUE(has(d.reason, "does not allow vehicle class passenger")) << d.reason;
    }
  EXPECT_EQ(closed, 2);
  EXPECT_EQ(m.junction_cell("j2"), -1);
  // disallow without passenger, or allow naming it: open.
  std::string open = line_net({"0", "2"}, "2");
  open.insert(open.find("<lane id=\"j0_j1_0\" ") + 19, "disallow=\"pedestrian\" ");
  open.insert(open.find("<lane id=\"j1_j0_0\" ") + 19, "allow=\"passenger truck\" ");
  EXPECT_EQ(gridify::gridify(test::temp_file("open.net.xml", open)).aisles.size(), 1u);
  // Every lane 0 a sidewalk, lane 1 the road: refused, naming lane 1.
  std::string walk = line_net({"0", "2"}, "2");
  for (const std::string e : {"j0_j1", "j1_j0"}) {
    const std::string lane = "<lane id=\"" + e + "_0\" index=\"0\" length=\"2\"/>";
    const size_t at = walk.find(lane);
    ASSERT_NE(at, std::string::npos);
    walk.replace(at, lane.size(), "<lane id=\"" + e + "_0\" index=\"0\" length=\"2\" allow=\"pedestrian\"/><lane id=\"" + e +
                                      "_1\" index=\"1\" length=\"2\"/>");
  }
  const std::string e = error_of(test::temp_file("walk.net.xml", walk));
  EXPECT_TRUE(has(e, "no aisles the AGVs may drive")) << e;
  EXPECT_TRUE(has(e, "lane 'j0_j1_1' allows them")) << e;
}

// An aisle within grid.tolerance of a whole number of cells is cut into equal steps that end
// exactly at its junctions (8.99 m of 1 m cells: steps of 0.99889 m). With steps of
// cell_length the junction sat 10 mm past the last step, and the controller's Safety saw an
// AGV standing at that junction as between two cells (exit 3, "not on its committed path").
TEST(GridifyErrors, AislesWithinTheToleranceEndAtTheirJunctions)
{
  GridifyOptions opt;
  opt.tolerance = 0.05;
  CellMap m = gridify::gridify(test::temp_file("tol.net.xml", line_net({"0", "8.99"}, "8.99")), opt);
  ASSERT_EQ(m.aisles.size(), 1u);
  const Aisle& a = m.aisles[0];
  EXPECT_EQ(a.steps, 9);
  EXPECT_FALSE(a.snapped);
  EXPECT_NEAR(a.spacing, 8.99 / 9, 1e-12);
  EXPECT_NEAR(a.steps * a.spacing, a.length_ab, 1e-9);
  ASSERT_EQ(a.cells.size(), 10u);  // j0, interior cells 1..8, j1
  const Cell& last = m.cells[a.cells[8]];  // k = 8, one step before junction j1
  EXPECT_NEAR(last.poses[0].pos, 8 * 8.99 / 9, 1e-12);
  EXPECT_NEAR(last.poses[1].pos, 8.99 / 9, 1e-12);
}
