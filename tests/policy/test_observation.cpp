// ObservationBuilder: exact windows on hand-made maps, including map borders.
#include <gtest/gtest.h>

#include <vector>

#include "policy/observation.hpp"
#include "test_util.hpp"

using namespace planner;
using namespace policy;

namespace {

// One channel of agent i's window, row by row.
std::vector<float> channel(const std::vector<float>& obs, const ObservationSpec& s, int agent, int c)
{
  const int area = s.window() * s.window();
  auto b = obs.begin() + static_cast<long>(agent) * s.size() + static_cast<long>(c) * area;
  return {b, b + area};
}

std::vector<float> build(const Graph& g, int radius, const Config& config, const Config& goals)
{
  ObservationSpec s;
  s.radius = radius;
  ObservationBuilder b(g, s);
  b.set_goals(goals);
  std::vector<float> obs(config.size() * static_cast<size_t>(s.size()), -7.0f);  // all overwritten
  b.build(config.data(), static_cast<int>(config.size()), obs.data());
  return obs;
}

}  // namespace

TEST(Observation, LayoutIsChannelRowColumn)
{
  ObservationSpec s;
  s.radius = 4;
  EXPECT_EQ(s.window(), 9);
  EXPECT_EQ(s.size(), 4 * 81);
  EXPECT_EQ(s.index(0, 0, 0), 0);
  EXPECT_EQ(s.index(0, 1, 0), 1);         // next column
  EXPECT_EQ(s.index(0, 0, 1), 9);         // next row
  EXPECT_EQ(s.index(2, 4, 4), 2 * 81 + 40);  // centre of channel 2
}

// Map (x = column, y = row):      agent 0 at (0,0) heading for (2,0);
//   . @ .                          agent 1 parked on its goal (1,1).
//   . . .
//   @ . .
TEST(Observation, ExactWindowsAtTheBorder)
{
  Graph g = test::grid({".@.", "...", "@.."});
  Config c = test::at(g, {{0, 0}, {1, 1}}), goals = test::at(g, {{2, 0}, {1, 1}});
  const auto obs = build(g, 1, c, goals);
  ObservationSpec s;
  s.radius = 1;

  // Agent 0 in the top-left corner: the row above and the column to the left are off the map.
  EXPECT_EQ(channel(obs, s, 0, kObstacle), (std::vector<float>{1, 1, 1, 1, 0, 1, 1, 0, 0}));
  EXPECT_EQ(channel(obs, s, 0, kAgent), (std::vector<float>{0, 0, 0, 0, 0, 0, 0, 0, 1}));
  EXPECT_EQ(channel(obs, s, 0, kParked), (std::vector<float>{0, 0, 0, 0, 0, 0, 0, 0, 1}));
  // d(0,0) = 4 (down, right, right, up); d(0,1) = 3, d(1,1) = 2; scale 2r = 2.
  EXPECT_EQ(channel(obs, s, 0, kGoalDistance), (std::vector<float>{1, 1, 1, 1, 0, 1, 1, -0.5f, -1}));

  // Agent 1 in the centre sees the whole map; agent 0 is not on its goal: not parked.
  EXPECT_EQ(channel(obs, s, 1, kObstacle), (std::vector<float>{0, 1, 0, 0, 0, 0, 1, 0, 0}));
  EXPECT_EQ(channel(obs, s, 1, kAgent), (std::vector<float>{1, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(channel(obs, s, 1, kParked), (std::vector<float>{0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(channel(obs, s, 1, kGoalDistance), (std::vector<float>{1, 1, 1, 0.5f, 0, 0.5f, 1, 0.5f, 1}));
}

TEST(Observation, BottomRightCornerAndSelfNotMarked)
{
  Graph g = test::grid({"...", "...", "..."});
  Config c = test::at(g, {{2, 2}, {1, 2}}), goals = test::at(g, {{2, 2}, {0, 0}});
  const auto obs = build(g, 1, c, goals);
  ObservationSpec s;
  s.radius = 1;
  EXPECT_EQ(channel(obs, s, 0, kObstacle), (std::vector<float>{0, 0, 1, 0, 0, 1, 1, 1, 1}));
  // Agent 0 is on its own goal: neither it nor its cell is marked in its own window.
  EXPECT_EQ(channel(obs, s, 0, kAgent), (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 0, 0}));
  EXPECT_EQ(channel(obs, s, 0, kParked), (std::vector<float>{0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(channel(obs, s, 0, kGoalDistance), (std::vector<float>{1, 0.5f, 1, 0.5f, 0, 1, 1, 1, 1}));
  // Agent 1 sees agent 0 parked on its goal at its right.
  EXPECT_EQ(channel(obs, s, 1, kParked), (std::vector<float>{0, 0, 0, 0, 0, 1, 0, 0, 0}));
  EXPECT_EQ(channel(obs, s, 1, kAgent), (std::vector<float>{0, 0, 0, 0, 0, 1, 0, 0, 0}));
  EXPECT_EQ(channel(obs, s, 1, kObstacle), (std::vector<float>{0, 0, 0, 0, 0, 0, 1, 1, 1}));
}

// A wall forces a detour: the goal two cells away is 8 steps away, so the distance signal
// saturates at -1 (clipped to 2r = 4 steps).
TEST(Observation, GoalDistanceIsClipped)
{
  Graph g = test::grid({".@.", ".@.", ".@.", "..."});
  Config c = test::at(g, {{0, 0}}), goals = test::at(g, {{2, 0}});
  const auto obs = build(g, 2, c, goals);
  ObservationSpec s;
  s.radius = 2;
  const auto d = channel(obs, s, 0, kGoalDistance);
  EXPECT_EQ(d[s.index(0, 2, 2)], 0.0f);     // centre
  EXPECT_EQ(d[s.index(0, 4, 2)], -1.0f);    // the goal (2,0): 0 - 8, clipped
  EXPECT_EQ(d[s.index(0, 4, 3)], -1.0f);    // (2,1): 1 - 8, clipped
  EXPECT_EQ(d[s.index(0, 2, 3)], -0.25f);   // (0,1): 7 - 8
  EXPECT_EQ(d[s.index(0, 3, 2)], 1.0f);     // (1,0) is a wall
  EXPECT_EQ(d[s.index(0, 0, 0)], 1.0f);     // off the map
}

TEST(Observation, UnreachableCellsLookFar)
{
  Graph g = test::grid({".@.", ".@.", ".@."});  // the right column is cut off
  Config c = test::at(g, {{0, 1}}), goals = test::at(g, {{0, 0}});
  const auto obs = build(g, 2, c, goals);
  ObservationSpec s;
  s.radius = 2;
  const auto d = channel(obs, s, 0, kGoalDistance), o = channel(obs, s, 0, kObstacle);
  EXPECT_EQ(d[s.index(0, 2, 1)], -0.25f);  // the goal (0,0): 0 - 1, scale 4
  EXPECT_EQ(d[s.index(0, 2, 3)], 0.25f);   // (0,2)
  EXPECT_EQ(o[s.index(0, 4, 2)], 0.0f);    // (2,1) is free ...
  EXPECT_EQ(d[s.index(0, 4, 2)], 1.0f);    // ... but unreachable
}

TEST(Observation, RejectsNonGridGraphsAndWrongAgentCount)
{
  Graph path = Graph::from_edges(3, {{0, 1}, {1, 2}});
  EXPECT_THROW(ObservationBuilder(path, ObservationSpec{}), std::invalid_argument);
  Graph g = test::grid({"..."});
  ObservationBuilder b(g, ObservationSpec{});
  b.set_goals(test::at(g, {{0, 0}}));
  std::vector<float> out(2 * ObservationSpec{}.size());
  Config c = test::at(g, {{1, 0}, {2, 0}});
  EXPECT_THROW(b.build(c.data(), 2, out.data()), std::logic_error);
}
