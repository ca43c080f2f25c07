// Safety on a real gridified net (no SUMO run): the cell-claim rule and its one exception,
// the members of a rotation group driving together. Regression for the huge AGV run that
// Safety stopped at t=1693.25 s ("agv60 and agv88 overlap at cell 2114", two AGVs one cell
// apart on one lane, in step): they were two members of a rotation group a->b->c->a,
// which the ADG starts together on purpose; Safety took their shared claim for a conflict.
#include <gtest/gtest.h>

#include "controller/safety.hpp"
#include "controller/sumo_error.hpp"
#include "gridify/gridifier.hpp"

using namespace controller;

namespace {

struct Lane {
  std::string id;
  double spacing = 0;
  std::vector<planner::Vertex> cells;
};

// An ab lane of an aisle with at least 3 cells (junction A, two interior cells).
Lane some_lane(const gridify::CellMap& map)
{
  for (const auto& [id, la] : map.lane_aisle) {
    const gridify::Aisle& a = map.aisles[la.first];
    if (la.second && a.cells.size() >= 3) return {id, a.spacing, a.cells};
  }
  return {};
}

std::string check(Safety& s, const Lane& l, double front0, double front1, const std::vector<int>& group)
{
  const std::vector<VehiclePose> poses = {{l.id, front0}, {l.id, front1}};
  const std::vector<std::vector<planner::Vertex>> allowed = {{l.cells[0], l.cells[1]}, {l.cells[1], l.cells[2]}};
  try {
    s.check(poses, allowed, {"agv0", "agv1"}, 1.0, true, group);
  } catch (const ControlError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Safety, RotationGroupMembersInMotionMayShareACellClaim)
{
  const gridify::CellMap map = gridify::gridify(std::string(RTLACAM_SCENARIOS) + "/small.net.xml");
  const Lane l = some_lane(map);
  ASSERT_FALSE(l.id.empty());
  Safety s(map, 0.3 * l.spacing);
  const double a = 0.5 * l.spacing, b = 1.5 * l.spacing;  // agv0 in (c0, c1), agv1 in (c1, c2)
  // Both claim c1: fine for two members of one rotation group ...
  EXPECT_EQ(check(s, l, a, b, {4, 4}), "");
  // ... a conflict otherwise: no group, different groups, one member only.
  for (const std::vector<int>& g : std::vector<std::vector<int>>{{}, {-1, -1}, {3, 4}, {4, -1}}) {
    const std::string e = check(s, l, a, b, g);
    EXPECT_NE(e.find("overlap at cell " + std::to_string(l.cells[1])), std::string::npos) << e;
  }
  // A member that landed on c1 a step before the other arrives (the full huge run's
  // t=3352.875 s overlap: its move came through a junction): still its group's ...
  EXPECT_EQ(check(s, l, l.spacing, b, {4, 4}), "");
  // ... but nobody else's.
  const std::string e = check(s, l, l.spacing, b, {4, 5});
  EXPECT_NE(e.find("overlap at cell " + std::to_string(l.cells[1])), std::string::npos) << e;
  EXPECT_EQ(s.checks(), 7);
}

// run.executor adg-follow: a follower may drive into the cell its leader is leaving, so
// Safety checks bodies around the cell instead of whole-cell claims -- and still fails on
// a body overlap, a head-on pass and two AGVs standing on one cell.
TEST(Safety, FollowingModeChecksBodiesAroundACellNotClaims)
{
  const gridify::CellMap map = gridify::gridify(std::string(RTLACAM_SCENARIOS) + "/small.net.xml");
  const Lane l = some_lane(map);
  ASSERT_FALSE(l.id.empty());
  const double s = l.spacing, len = 0.3 * s;
  Safety safety(map, len);
  safety.set_following(true);
  const auto at = [&](int k) { return l.cells[k]; };
  // agv0 in (c0, c1) heading to c1, agv1 in (c1, c2) leaving c1: a gap of b - a - len.
  EXPECT_EQ(check(safety, l, 0.5 * s, 1.5 * s, {}), "");  // exclusive claims would fail here
  EXPECT_EQ(check(safety, l, 0.7 * s, 0.7 * s + len + 1e-6, {}), "");
  std::string e = check(safety, l, 0.8 * s, 0.8 * s + 0.9 * len, {});
  EXPECT_NE(e.find("overlap (bodies intersect) at cell " + std::to_string(at(1))), std::string::npos) << e;
  // Both standing on c1.
  e = check(safety, l, s, s, {});
  EXPECT_NE(e.find("overlap"), std::string::npos) << e;
  // Head-on: agv1 on the opposite lane between c1 and c0, heading to c0, while agv0 heads
  // from c0 to c1 (far enough apart that no body is near the other's).
  const gridify::Aisle& ai = map.aisles[map.lane_aisle.at(l.id).first];
  const std::vector<VehiclePose> poses = {{l.id, 0.1 * s}, {ai.lane_ba, ai.length_ba - 0.9 * s}};
  const std::vector<std::vector<planner::Vertex>> allowed = {{at(0), at(1)}, {at(1), at(0)}};
  e.clear();
  try {
    safety.check(poses, allowed, {"agv0", "agv1"}, 1.0, true, {});
  } catch (const ControlError& x) {
    e = x.what();
  }
  EXPECT_NE(e.find("pass head-on"), std::string::npos) << e;
}
