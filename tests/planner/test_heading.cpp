// planner/heading.hpp: the rotation geometry every layer shares, against LoRR's
// ActionModelWithRotate::result_state (0 east, 1 south, 2 west, 3 north; R clockwise).
#include <gtest/gtest.h>

#include <stdexcept>

#include "grid.hpp"
#include "planner/heading.hpp"

using namespace planner;

TEST(Heading, TurnsAndQuarterTurns)
{
  for (int h = 0; h < 4; ++h) {
    EXPECT_EQ(turned_ccw(turned_cw(h)), h);
    EXPECT_EQ(reversed(reversed(h)), h);
    EXPECT_EQ(heading_after(h, 'F'), h);
    EXPECT_EQ(heading_after(h, 'W'), h);
    EXPECT_EQ(quarter_turns(h, h), 0);
    EXPECT_EQ(quarter_turns(h, turned_cw(h)), 1);
    EXPECT_EQ(quarter_turns(h, turned_ccw(h)), 1);
    EXPECT_EQ(quarter_turns(h, reversed(h)), 2);
    EXPECT_EQ(turn_toward(h, turned_ccw(h)), 'C');
    EXPECT_EQ(turn_toward(h, turned_cw(h)), 'R');
    EXPECT_EQ(turn_toward(h, reversed(h)), 'R');  // a half turn goes clockwise
  }
  EXPECT_EQ(heading_after(0, 'R'), 1);  // east, clockwise: south
  EXPECT_EQ(heading_after(0, 'C'), 3);  // east, counter-clockwise: north
}

TEST(Heading, ResultStateFollowsLorr)
{
  // 3 x 2 grid with a wall at (1, 1):  . . .
  //                                    . # .
  const Graph g = test::grid({"...", ".#."});
  const Vertex a = g.at(0, 0), b = g.at(1, 0), c = g.at(0, 1);
  EXPECT_EQ(result_state(g, {a, 0}, 'F'), (Pose{b, 0}));     // east: +x
  EXPECT_EQ(result_state(g, {a, 1}, 'F'), (Pose{c, 1}));     // south: +y
  EXPECT_EQ(result_state(g, {a, 2}, 'F').v, -1);             // west: off the map
  EXPECT_EQ(result_state(g, {b, 1}, 'F').v, -1);             // south of b: the wall
  EXPECT_EQ(result_state(g, {a, 0}, 'R'), (Pose{a, 1}));     // turns keep the cell
  EXPECT_EQ(result_state(g, {a, 0}, 'C'), (Pose{a, 3}));
  EXPECT_EQ(result_state(g, {a, 2}, 'W'), (Pose{a, 2}));
  for (int h = 0; h < 4; ++h) {
    const Vertex u = cell_ahead(g, b, h);
    if (u >= 0) {
      EXPECT_EQ(heading_of_move(g, b, u), h);
    }
  }
  EXPECT_THROW(heading_of_move(g, a, g.at(2, 0)), std::invalid_argument);
}
