// netgenerate grids: cell and edge counts and per-cell degrees against closed forms.
// A grid of X x Y nodes L metres apart has A = (X-1)Y + X(Y-1) aisles; with n = L/c steps
// per aisle: cells = XY + (n-1)A, edges = nA, a junction cell's degree is its node's
// degree (2 at corners, 3 on borders, 4 inside) and an aisle cell's degree is 2.
#include <chrono>
#include <cmath>

#include "gridify/gridifier.hpp"
#include "gridify/movingai_map.hpp"
#include "gridify_test_util.hpp"
#include "planner/movingai.hpp"

using namespace gridify;
using namespace gridify_test;

namespace {

void check_closed_form(const std::string& net_path, int X, int Y, double L, double c)
{
  GridifyOptions opt;
  opt.cell_length = c;
  NetFile net = NetFile::read(net_path);
  CellMap m = gridify::gridify(net, opt);
  const int n = static_cast<int>(std::lround(L / c));
  const int A = (X - 1) * Y + X * (Y - 1);
  EXPECT_EQ(static_cast<int>(m.aisles.size()), A);
  EXPECT_EQ(m.num_junction_cells(), X * Y);
  EXPECT_EQ(static_cast<int>(m.cells.size()), X * Y + (n - 1) * A);
  EXPECT_EQ(static_cast<int>(m.graph.num_edges()), n * A);
  EXPECT_TRUE(m.dropped.empty());
  for (planner::Vertex v = 0; v < m.graph.size(); ++v) {
    const Cell& cell = m.cells[v];
    if (cell.kind == CellKind::Aisle) {
      EXPECT_EQ(m.graph.degree(v), 2) << v;
    } else {
      // Node column/row from its position (netgenerate puts node (i, j) at (i L, j L)).
      int i = static_cast<int>(std::lround(cell.x / L)), j = static_cast<int>(std::lround(cell.y / L));
      int deg = (i > 0) + (i < X - 1) + (j > 0) + (j < Y - 1);
      EXPECT_EQ(m.graph.degree(v), deg) << cell.junction;
    }
  }
  expect_invariants(m, net);
  // The grid exports to a MovingAI map with the same graph size.
  GridLayout g = grid_layout(m);
  EXPECT_EQ(g.width, (X - 1) * n + 1);
  EXPECT_EQ(g.height, (Y - 1) * n + 1);
}

}  // namespace

TEST(GridifyGrid, CommittedGrid4x3)
{
  check_closed_form(data("grid4x3.net.xml"), 4, 3, 5.0, 1.0);
}

TEST(GridifyGrid, CommittedGrid4x3HalfMetreCells)
{
  check_closed_form(data("grid4x3.net.xml"), 4, 3, 5.0, 0.5);
}

TEST(GridifyGrid, CommittedGrid4x3FiveMetreCells)
{
  check_closed_form(data("grid4x3.net.xml"), 4, 3, 5.0, 5.0);  // n = 1: junctions only
}

struct GridCase {
  int x, y;
  double length, cell;
};

void PrintTo(const GridCase& g, std::ostream* os)
{
  *os << g.x << "x" << g.y << " nodes, " << g.length << " m aisles, cell " << g.cell;
}

class GridifyNetgenerate : public ::testing::TestWithParam<GridCase> {};

TEST_P(GridifyNetgenerate, ClosedForms)
{
  if (!have_netgenerate()) GTEST_SKIP() << "netgenerate not installed";
  GridCase g = GetParam();
  std::string net = netgenerate_grid(temp_dir(), g.x, g.y, g.length);
  check_closed_form(net, g.x, g.y, g.length, g.cell);
}

INSTANTIATE_TEST_SUITE_P(Sizes, GridifyNetgenerate,
                         ::testing::Values(GridCase{2, 2, 1, 1}, GridCase{2, 3, 3, 1}, GridCase{3, 4, 3, 1},
                                           GridCase{5, 5, 5, 1}, GridCase{7, 3, 4, 2}, GridCase{6, 6, 2, 0.5},
                                           GridCase{10, 10, 5, 1}),
                         [](const ::testing::TestParamInfo<GridCase>& i) {
                           // e.g. 6x6_L2_c0p5 (node counts, aisle length, cell length)
                           auto f = [](double d) {
                             std::string s = std::to_string(d);
                             s.erase(s.find_last_not_of('0') + 1);
                             if (s.back() == '.') s.pop_back();
                             for (char& ch : s) if (ch == '.') ch = 'p';
                             return s;
                           };
                           return std::to_string(i.param.x) + "x" + std::to_string(i.param.y) + "_L" +
                                  f(i.param.length) + "_c" + f(i.param.cell);
                         });

// The speed target: a 21x21 grid (1680 edges) in well under a second.
TEST(GridifyGrid, Grid21Speed)
{
  if (!have_netgenerate()) GTEST_SKIP() << "netgenerate not installed";
  std::string net = netgenerate_grid(temp_dir(), 21, 21, 5);
  auto t0 = std::chrono::steady_clock::now();
  CellMap m = gridify::gridify(net);
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("gridify grid21 (1680 edges): %zu cells, %zu graph edges in %.1f ms\n", m.cells.size(),
              m.graph.num_edges(), ms);
  RecordProperty("gridify_ms", std::to_string(ms));
  EXPECT_EQ(m.cells.size(), 441u + 840u * 4u);
  EXPECT_LT(ms, 1000.0);
}

// Multi-lane edges: AGVs use lane 0; the gridifier says so instead of staying silent.
TEST(GridifyGrid, MultiLaneEdgesAreNamedInAWarning)
{
  if (!have_netgenerate()) GTEST_SKIP() << "netgenerate not installed";
  std::string net = netgenerate_grid(temp_dir(), 3, 3, 2, 2);
  CellMap m = gridify::gridify(net);
  bool named = false;
  for (const std::string& w : m.warnings) named |= w.find("24 edge(s) with more than one lane, e.g.") != std::string::npos &&
                                                   w.find("(2 lanes); AGVs use lane 0") != std::string::npos;
  EXPECT_TRUE(named) << (m.warnings.empty() ? "no warnings" : m.warnings.front());
  for (const Cell& c : m.cells)
    for (const auto& p : c.poses) EXPECT_EQ(p.lane.substr(p.lane.size() - 2), "_0") << p.lane;
  expect_invariants(m, gridify::NetFile::read(net));
}

// The exported MovingAI map loads with the planner's reader into the same graph shape.
TEST(GridifyGrid, MovingAiRoundTrip)
{
  CellMap m = gridify::gridify(data("grid4x3.net.xml"));
  std::string path = temp_dir() + "/grid4x3.map";
  write_movingai_map(m, path);
  planner::Graph g = planner::load_map(path);
  EXPECT_EQ(g.size(), m.graph.size());
  EXPECT_EQ(g.num_edges(), m.graph.num_edges());
  EXPECT_EQ(g.width(), 16);
  EXPECT_EQ(g.height(), 11);
}

TEST(GridifyGrid, LatticeNetsGetTheGridView)
{
  CellMap m = gridify::gridify(data("grid4x3.net.xml"));
  ASSERT_TRUE(m.graph.is_grid());
  EXPECT_EQ(m.graph.width(), 16);
  EXPECT_EQ(m.graph.height(), 11);
  // Same lattice as the MovingAI export: every vertex's cell is free there, with the same
  // neighbours.
  std::string path = temp_dir() + "/grid4x3_view.map";
  write_movingai_map(m, path);
  planner::Graph g = planner::load_map(path);
  for (planner::Vertex v = 0; v < m.graph.size(); ++v) {
    const int x = m.graph.cell_x(v), y = m.graph.cell_y(v);
    ASSERT_EQ(m.graph.at(x, y), v);
    planner::Vertex w = g.at(x, y);
    ASSERT_GE(w, 0);
    EXPECT_EQ(m.graph.degree(v), g.degree(w));
  }
  // Cell rows grow downwards while SUMO's y grows upwards.
  planner::Vertex top = 0;
  for (planner::Vertex v = 0; v < m.graph.size(); ++v)
    if (m.graph.position(v).y > m.graph.position(top).y) top = v;
  EXPECT_EQ(m.graph.cell_y(top), 0);
}
