#pragma once
// The warehouse traffic rules a SUMO additional file can carry in SUMO's own forms
// (controller/rules.hpp turns them into cells):
//  - closures: <rerouter> <interval begin end> with <closingReroute id=EDGE> or
//    <closingLaneReroute id=LANE> children -- the edges / lanes are closed for the AGVs
//    (SUMO's default: closed for every class but "authority") from begin to end (s; end
//    omitted: the rest of the run). A closingReroute whose `allow` names "passenger" (the
//    AGVs' class) or whose `disallow` names neither it nor "all" does not close it for AGVs.
//  - one-at-a-time zones: <poly type="rtlacam.zone" shape="x,y x,y ..."> -- at most one
//    AGV inside (the cells whose centre lies inside the polygon).
// Only the form is checked here ("file:line: what" InputError: a missing id, a bad number,
// an interval ending before it begins, a zone polygon with fewer than 3 points); whether an
// edge or lane exists is the caller's check (it knows the gridified net).
#include <string>
#include <vector>

#include "planner/graph.hpp"

namespace gridify {

inline constexpr const char* kZoneType = "rtlacam.zone";

struct SumoClosure {
  std::string source;               // "file.add.xml:12: rerouter 'r1'" (for messages)
  std::vector<std::string> edges;   // closingReroute ids
  std::vector<std::string> lanes;   // closingLaneReroute ids
  double begin = 0, end = 0;        // s; end = +infinity when omitted
};

struct SumoZone {
  std::string id;
  std::string source;               // "file.add.xml:20: poly 'z1'"
  std::vector<planner::Point> shape;
};

struct SumoRules {
  std::vector<SumoClosure> closures;
  std::vector<SumoZone> zones;
};

// Reads the rules of `path` (other elements are ignored). Throws planner::InputError.
SumoRules read_sumo_rules(const std::string& path);

// Whether (x, y) lies inside the polygon (even-odd rule; the polygon is closed implicitly).
bool inside(const std::vector<planner::Point>& poly, double x, double y);

}  // namespace gridify
