// The warehouse scenarios in sumo_scenarios/: counts, stations and invariants.
// small: 4 picking aisles of 8 m between shelf blocks, cross aisles 4 m apart (3 cells
// between columns), 4 stub aisles of 2 m to stations.
//   junctions 8 + 4 stubs = 12; aisles 6 cross + 4 picking + 4 stubs = 14;
//   aisle cells 6*3 + 4*7 + 4*1 = 50; edges 6*4 + 4*8 + 4*2 = 64.
// large: 16 columns x 3 cross aisles (y = 0, 12, 24), 16 stubs of 3 m.
//   junctions 48 + 16 = 64; aisles 3*15 + 16*2 + 16 = 93;
//   aisle cells 45*3 + 32*11 + 16*2 = 519; edges 45*4 + 32*12 + 16*3 = 612.
#include "gridify/gridifier.hpp"
#include "gridify/movingai_map.hpp"
#include "gridify_test_util.hpp"

using namespace gridify;
using namespace gridify_test;

namespace {

CellMap load(const std::string& name, NetFile* net_out = nullptr)
{
  NetFile net = NetFile::read(scenario(name + ".net.xml"));
  GridifyOptions opt;
  opt.additional = scenario(name + ".add.xml");
  CellMap m = gridify::gridify(net, opt);
  if (net_out) *net_out = std::move(net);
  return m;
}

const Station* station(const CellMap& m, const std::string& id)
{
  for (const Station& s : m.stations)
    if (s.id == id) return &s;
  return nullptr;
}

}  // namespace

TEST(GridifyScenarios, Small)
{
  NetFile net;
  CellMap m = load("small", &net);
  EXPECT_EQ(m.num_junction_cells(), 12);
  EXPECT_EQ(m.aisles.size(), 14u);
  EXPECT_EQ(m.num_aisle_cells(), 50);
  EXPECT_EQ(m.graph.num_edges(), 64u);
  EXPECT_TRUE(m.dropped.empty());
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
  expect_invariants(m, net);

  // Stations at the ends of the stubs: on the stub's dead-end junction cell.
  ASSERT_EQ(m.stations.size(), 5u);
  const Station* p1 = station(m, "pickup1");
  ASSERT_NE(p1, nullptr);
  EXPECT_EQ(p1->kind, "pickup");
  EXPECT_EQ(p1->element, "busStop");
  EXPECT_EQ(p1->cell, m.junction_cell("pick1"));
  EXPECT_EQ(m.graph.degree(p1->cell), 1);
  const Station* d3 = station(m, "drop3");
  ASSERT_NE(d3, nullptr);
  EXPECT_EQ(d3->cell, m.junction_cell("drop3"));
  // park0: a parkingArea on c0r0_c0r1 covering [2.5, 3]: the aisle cell 3 m up.
  const Station* park = station(m, "park0");
  ASSERT_NE(park, nullptr);
  EXPECT_EQ(park->kind, "parking");
  const Cell& pc = m.cells[park->cell];
  EXPECT_EQ(pc.kind, CellKind::Aisle);
  EXPECT_DOUBLE_EQ(pc.x, 0.0);
  EXPECT_DOUBLE_EQ(pc.y, 3.0);
  EXPECT_EQ(pc.poses[0].lane, "c0r0_c0r1_0");
  EXPECT_DOUBLE_EQ(pc.poses[0].pos, 3.0);
  EXPECT_EQ(pc.poses[1].lane, "c0r1_c0r0_0");
  EXPECT_DOUBLE_EQ(pc.poses[1].pos, 5.0);
  ASSERT_EQ(pc.stations.size(), 1u);

  // Axis-aligned: 13 x 13 lattice (x 0..12, y -2..10).
  GridLayout g = grid_layout(m);
  EXPECT_EQ(g.width, 13);
  EXPECT_EQ(g.height, 13);
}

TEST(GridifyScenarios, Large)
{
  NetFile net;
  CellMap m = load("large", &net);
  EXPECT_EQ(m.num_junction_cells(), 64);
  EXPECT_EQ(m.aisles.size(), 93u);
  EXPECT_EQ(m.num_aisle_cells(), 519);
  EXPECT_EQ(m.cells.size(), 583u);
  EXPECT_EQ(m.graph.num_edges(), 612u);
  EXPECT_TRUE(m.dropped.empty());
  EXPECT_EQ(m.stations.size(), 20u);
  int pickups = 0, drops = 0, parking = 0;
  for (const Station& s : m.stations) {
    pickups += s.kind == "pickup";
    drops += s.kind == "drop";
    parking += s.kind == "parking";
    EXPECT_GE(s.cell, 0);
  }
  EXPECT_EQ(pickups, 8);
  EXPECT_EQ(drops, 8);
  EXPECT_EQ(parking, 4);
  expect_invariants(m, net);
  EXPECT_EQ(grid_layout(m).width, 61);
}
