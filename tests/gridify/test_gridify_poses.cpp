// Cell <-> SUMO pose mapping (the controller commands these):
//   aisle cell k heading A->B: (AB_0, k*cell); heading B->A: (BA_0, L - k*cell);
//   junction cell reached over edge E: (E_0, L_E).
#include "gridify/gridifier.hpp"
#include "gridify_test_util.hpp"

using namespace gridify;
using namespace gridify_test;

namespace {

void expect_pose(const SumoPose& p, const std::string& lane, double pos)
{
  EXPECT_EQ(p.lane, lane);
  EXPECT_DOUBLE_EQ(p.pos, pos) << lane;
}

}  // namespace

TEST(GridifyPoses, EveryAisleCellAndHeading)
{
  for (double c : {1.0, 0.5, 2.5}) {
    GridifyOptions opt;
    opt.cell_length = c;
    CellMap m = gridify::gridify(data("grid4x3.net.xml"), opt);
    for (const Aisle& a : m.aisles) {
      ASSERT_EQ(a.steps, static_cast<int>(5.0 / c));
      ASSERT_EQ(a.cells.size(), static_cast<size_t>(a.steps + 1));
      EXPECT_EQ(m.cells[a.cells.front()].junction, a.a);
      EXPECT_EQ(m.cells[a.cells.back()].junction, a.b);
      EXPECT_EQ(a.lane_ab, a.ab + "_0");
      EXPECT_EQ(a.lane_ba, a.ba + "_0");
      for (int k = 1; k < a.steps; ++k) {
        const Cell& cell = m.cells[a.cells[k]];
        EXPECT_EQ(cell.k, k);
        expect_pose(cell.poses[0], a.lane_ab, k * c);
        expect_pose(cell.poses[1], a.lane_ba, a.length_ba - k * c);
        // Moving A->B into cell k comes from k-1; B->A from k+1.
        expect_pose(m.pose_entering(a.cells[k - 1], a.cells[k]), a.lane_ab, k * c);
        expect_pose(m.pose_entering(a.cells[k + 1], a.cells[k]), a.lane_ba, a.length_ba - k * c);
        // And the cell is found again from either pose.
        EXPECT_EQ(m.locate(a.lane_ab, k * c), a.cells[k]);
        EXPECT_EQ(m.locate(a.lane_ba, a.length_ba - k * c), a.cells[k]);
      }
      // Junction cells reached over the aisle: the end of the arriving lane.
      expect_pose(m.pose_entering(a.cells[a.steps - 1], a.cells.back()), a.lane_ab, a.length_ab);
      expect_pose(m.pose_entering(a.cells[1], a.cells.front()), a.lane_ba, a.length_ba);
    }
  }
}

TEST(GridifyPoses, ConcreteCellsOfGrid4x3)
{
  CellMap m = gridify::gridify(data("grid4x3.net.xml"));
  // Cell 2 m east of A0 on the aisle A0-B0.
  planner::Vertex v = m.locate("A0B0_0", 2.0);
  ASSERT_GE(v, 0);
  EXPECT_DOUBLE_EQ(m.cells[v].x, 2.0);
  EXPECT_DOUBLE_EQ(m.cells[v].y, 0.0);
  expect_pose(m.cells[v].poses[0], "A0B0_0", 2.0);
  expect_pose(m.cells[v].poses[1], "B0A0_0", 3.0);
  EXPECT_EQ(m.locate("B0A0_0", 3.0), v);
  EXPECT_EQ(m.locate("A0B0_0", 2.3), v);  // nearest cell
  // Lane ends are the junctions.
  EXPECT_EQ(m.locate("A0B0_0", 5.0), m.junction_cell("B0"));
  EXPECT_EQ(m.locate("A0B0_0", 0.2), m.junction_cell("A0"));
  EXPECT_EQ(m.locate("B0A0_0", 5.0), m.junction_cell("A0"));
  EXPECT_EQ(m.locate("nowhere_0", 1.0), -1);

  // Interior junction B1: reached over each of its 4 incoming edges at their ends; SUMO
  // has all 16 movements there (s, l, r and the turnaround t for each incoming edge).
  planner::Vertex b1 = m.junction_cell("B1");
  ASSERT_GE(b1, 0);
  const Cell& j = m.cells[b1];
  EXPECT_EQ(j.kind, CellKind::Junction);
  EXPECT_DOUBLE_EQ(j.x, 5.0);
  EXPECT_DOUBLE_EQ(j.y, 5.0);
  ASSERT_EQ(j.poses.size(), 4u);
  for (const SumoPose& p : j.poses) {
    EXPECT_DOUBLE_EQ(p.pos, 5.0);
    EXPECT_EQ(p.lane.substr(2, 2), "B1");  // edges XnB1
  }
  EXPECT_EQ(j.movements.size(), 16u);
  int turnarounds = 0;
  for (const Movement& mv : j.movements) turnarounds += mv.dir == "t";
  EXPECT_EQ(turnarounds, 4);
  // Corner A0 (degree 2) has its turnarounds too, thanks to --no-turnarounds.geometry false.
  EXPECT_EQ(m.cells[m.junction_cell("A0")].movements.size(), 4u);
  EXPECT_TRUE(m.warnings.empty());

  // Not adjacent: an error, not a made-up pose.
  EXPECT_THROW(m.pose_entering(m.junction_cell("A0"), b1), std::invalid_argument);
}

TEST(GridifyPoses, JunctionToJunctionAisles)
{
  // cell_length == aisle length: no aisle cells, junction cells are adjacent.
  GridifyOptions opt;
  opt.cell_length = 5;
  CellMap m = gridify::gridify(data("grid4x3.net.xml"), opt);
  planner::Vertex a0 = m.junction_cell("A0"), b0 = m.junction_cell("B0");
  ASSERT_TRUE(m.graph.adjacent(a0, b0));
  expect_pose(m.pose_entering(a0, b0), "A0B0_0", 5.0);
  expect_pose(m.pose_entering(b0, a0), "B0A0_0", 5.0);
}

TEST(GridifyPoses, StationsOnTinyNet)
{
  GridifyOptions opt;
  opt.additional = data("tiny_stations.add.xml");
  CellMap m = gridify::gridify(data("tiny.net.xml"), opt);
  ASSERT_EQ(m.stations.size(), 4u);
  // busStop on b_a_0 [2.5, 3]: middle 2.75 from b, i.e. 0.25 from a: junction a.
  EXPECT_EQ(m.stations[0].id, "stopA");
  EXPECT_EQ(m.stations[0].kind, "pickup");
  EXPECT_EQ(m.stations[0].cell, m.junction_cell("a"));
  // parkingArea on a_b_0 [1.5, 2.5]: aisle cell k = 2.
  EXPECT_EQ(m.stations[1].kind, "parking");
  EXPECT_EQ(m.stations[1].cell, m.aisles[0].cells[2]);
  // poi by x, y next to b, with type="drop".
  EXPECT_EQ(m.stations[2].kind, "drop");
  EXPECT_EQ(m.stations[2].cell, m.junction_cell("b"));
  // poi on a lane position.
  EXPECT_EQ(m.stations[3].kind, "poi");
  EXPECT_EQ(m.stations[3].cell, m.aisles[0].cells[1]);
  EXPECT_EQ(m.cells[m.junction_cell("a")].stations, std::vector<int>{0});
}
