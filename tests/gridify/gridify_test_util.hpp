#pragma once
// Shared helpers of the gridify tests: fixture paths, netgenerate grids in a per-test
// temporary directory, and the invariants every gridification must satisfy.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "gridify/cell_map.hpp"
#include "gridify/net_file.hpp"

namespace gridify_test {

inline std::string data(const std::string& f) { return std::string(RTLACAM_TEST_DATA) + "/gridify/" + f; }
inline std::string scenario(const std::string& f) { return std::string(RTLACAM_SCENARIOS) + "/" + f; }

// A fresh directory for this test (ctest runs each TEST in its own process).
inline std::string temp_dir()
{
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string d = ::testing::TempDir() + "gridify_" + info->test_suite_name() + "_" + info->name() + "_" +
                  std::to_string(getpid());
  std::system(("rm -rf '" + d + "' && mkdir -p '" + d + "'").c_str());
  return d;
}

inline bool have_netgenerate() { return std::string(RTLACAM_NETGENERATE).size() > 0; }

// netgenerate grid of nx x ny nodes, `length` metres apart, with the options of
// /work/shared/notes/sumo-1.15.md (no internal links, radius 0, turnarounds everywhere).
inline std::string netgenerate_grid(const std::string& dir, int nx, int ny, double length, int lanes = 1)
{
  setenv("SUMO_HOME", "/usr/share/sumo", 0);
  std::string out = dir + "/grid" + std::to_string(nx) + "x" + std::to_string(ny) + ".net.xml";
  std::string cmd = std::string(RTLACAM_NETGENERATE) + " --grid --grid.x-number " + std::to_string(nx) +
                    " --grid.y-number " + std::to_string(ny) + " --grid.length " + std::to_string(length) +
                    " --default.lanenumber " + std::to_string(lanes) + " --default.lanewidth 1.0 --default.speed 1.0"
                    " --default-junction-type unregulated --no-internal-links"
                    " --default.junctions.radius 0 --junctions.corner-detail 0 --no-turnarounds.geometry false"
                    " -o '" + out + "' > '" + dir + "/netgenerate.log' 2>&1";
  int rc = std::system(cmd.c_str());
  EXPECT_EQ(rc, 0) << cmd;
  return out;
}

// Invariants: connected, every cell has its SUMO poses on real lanes within [0, length],
// every graph edge can be driven both ways in SUMO (lanes exist and, at a junction cell,
// a connection leads into the aisle and one leads out of the arriving lane).
inline void expect_invariants(const gridify::CellMap& m, const gridify::NetFile& net)
{
  using namespace gridify;
  ASSERT_EQ(m.graph.size(), static_cast<int>(m.cells.size()));
  int comps = 0;
  m.graph.strong_components(&comps);  // every cell reaches every other (one-way aisles too)
  EXPECT_EQ(comps, 1);
  auto lane_length = [&](const std::string& lane) {
    for (const NetEdge& e : net.edges)
      for (const NetLane& l : e.lanes)
        if (l.id == lane) return l.length;
    ADD_FAILURE() << "unknown lane " << lane;
    return -1.0;
  };
  auto edge_of = [&](const std::string& lane) { return lane.substr(0, lane.rfind('_')); };
  for (planner::Vertex v = 0; v < m.graph.size(); ++v) {
    const Cell& c = m.cells[v];
    EXPECT_GE(m.graph.degree(v), 1) << v;
    if (c.kind == CellKind::Aisle) EXPECT_EQ(c.poses.size(), m.aisles[c.aisle].one_way ? 1u : 2u);
    else EXPECT_GE(c.poses.size(), 1u);
    for (const SumoPose& p : c.poses) {
      double L = lane_length(p.lane);
      EXPECT_GE(p.pos, 0.0) << p.lane;
      EXPECT_LE(p.pos, L + 1e-9) << p.lane;
    }
    for (planner::Vertex u : m.graph.neighbors(v)) {
      // Two-way unless both cells lie on one one-way aisle (a one-way aisle's arcs go A->B).
      const bool two_way = m.graph.adjacent(u, v);
      const int aisle = c.kind == CellKind::Aisle ? c.aisle : m.cells[u].aisle;
      if (aisle >= 0 && !m.aisles[aisle].one_way) {
        EXPECT_TRUE(two_way);
      }
      SumoPose there = m.pose_entering(v, u);
      EXPECT_GE(there.pos, 0.0);
      EXPECT_LE(there.pos, lane_length(there.lane) + 1e-9);
      SumoPose back = two_way ? m.pose_entering(u, v) : SumoPose{};
      if (two_way) {
        EXPECT_LE(back.pos, lane_length(back.lane) + 1e-9);
      }
      if (c.kind == CellKind::Junction) {
        // Leaving junction v into u: some connection at v leads into the lane of u's pose
        // (or, when u is a junction too, into the aisle edge from v to u).
        std::string into = edge_of(there.lane);
        if (m.cells[u].kind == CellKind::Junction)
          for (const NetEdge& x : net.edges)
            if (x.from == c.junction && x.to == m.cells[u].junction) into = x.id;
        bool enter = false, leave = false;
        for (const Movement& mv : c.movements) {
          enter |= mv.to == into;
          leave |= mv.from == edge_of(back.lane);
        }
        EXPECT_TRUE(enter) << "no connection into " << into << " at " << c.junction;
        if (two_way) {
          EXPECT_TRUE(leave) << "no connection out of " << back.lane << " at " << c.junction;
        }
      }
    }
  }
}

}  // namespace gridify_test
