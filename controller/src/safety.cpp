#include "controller/safety.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "controller/sumo_error.hpp"

namespace controller {

Safety::Safety(const gridify::CellMap& map, double length)
    : map_(map), length_(length), owner_(map.graph.size(), -1), stamp_(map.graph.size(), 0)
{
}

Claim Safety::locate(const std::string& lane, double pos) const
{
  auto it = map_.lane_aisle.find(lane);
  if (it == map_.lane_aisle.end()) return {};
  return locate(*it, pos);
}

Claim Safety::locate(const std::pair<const std::string, std::pair<int, bool>>& lane, double pos) const
{
  const gridify::Aisle& a = map_.aisles[lane.second.first];
  // Offset from junction A in cells.
  const double k = (lane.second.second ? pos : a.length_ba - pos) / a.spacing;
  const double kc = std::min<double>(std::max(k, 0.0), a.steps);
  const double r = std::round(kc);
  // At the lane's end (a junction cell) 1.1 mm count as on the cell: SUMO keeps the front
  // of an AGV held at an angle there (Commander::orient, set_angle) 1 mm (POSITION_EPS) back.
  const double lane_end = lane.second.second ? a.steps : 0;
  const double tol = r == lane_end ? 1.1e-3 : 1e-6;
  if (std::fabs(kc - r) * a.spacing <= tol) return {a.cells[static_cast<size_t>(r)], -1};
  const size_t lo = static_cast<size_t>(std::floor(kc));
  return {a.cells[lo], a.cells[std::min(lo + 1, a.cells.size() - 1)]};
}

void Safety::check(const std::vector<VehiclePose>& poses, const std::vector<std::vector<planner::Vertex>>& allowed,
                   const std::vector<std::string>& ids, double t, bool exclusive, const std::vector<int>& group)
{
  auto group_of = [&](int i) { return static_cast<size_t>(i) < group.size() ? group[i] : -1; };
  ++checks_;
  ++epoch_;
  char when[64];
  std::snprintf(when, sizeof when, "t=%.3f s: ", t);
  // (lane key, back, front, agent); lane key = 2 x aisle + (ab lane).
  bodies_.clear();
  near_.clear();
  for (int i = 0; i < static_cast<int>(poses.size()); ++i) {
    // Most AGVs stay on their lane from one step to the next: skip the hash lookup then.
    if (static_cast<size_t>(i) >= lane_cache_.size()) lane_cache_.resize(i + 1, map_.lane_aisle.end());
    auto la = lane_cache_[i];
    if (la == map_.lane_aisle.end() || la->first != poses[i].lane) la = lane_cache_[i] = map_.lane_aisle.find(poses[i].lane);
    const Claim c = la == map_.lane_aisle.end() ? Claim{} : locate(*la, poses[i].pos);
    if (c.a < 0)
      throw ControlError(when + std::string("AGV ") + ids[i] + " is off the aisles (lane '" + poses[i].lane + "')");
    for (planner::Vertex v : {c.a, c.b}) {
      if (v < 0) continue;
      const auto& al = allowed[i];
      if (std::find(al.begin(), al.end(), v) == al.end())
        throw ControlError(when + std::string("AGV ") + ids[i] + " is at cell " + std::to_string(v) + " (lane " +
                           poses[i].lane + " pos " + std::to_string(poses[i].pos) +
                           "), not on its committed path");
      if (following_ && c.b >= 0) continue;  // shared claims: check_following() below
      if (exclusive || c.b < 0) {
        // Two members of one unfinished rotation group: shared by design (one may land on
        // its cell a SUMO step before the other, whose move went through a junction).
        const bool rotating = stamp_[v] == epoch_ && group_of(i) >= 0 && group_of(i) == group_of(owner_[v]);
        if (stamp_[v] == epoch_ && !rotating) last_overlap_ = {owner_[v], i};
        if (stamp_[v] == epoch_ && !rotating)
          throw ControlError(when + std::string("AGVs ") + ids[owner_[v]] + " and " + ids[i] + " overlap at cell " +
                             std::to_string(v) + " (" + poses[owner_[v]].lane + " " + std::to_string(poses[owner_[v]].pos) +
                             ", " + poses[i].lane + " " + std::to_string(poses[i].pos) + ")");
        stamp_[v] = epoch_;
        owner_[v] = i;
      }
    }
    if (following_ && c.b >= 0) {
      // Direction of travel from the lane: A->B lanes run toward higher aisle offsets.
      const gridify::Aisle& ai = map_.aisles[la->second.first];
      const double k = (la->second.second ? poses[i].pos : ai.length_ba - poses[i].pos) / ai.spacing;
      const double frac = (k - std::floor(k)) * ai.spacing;  // front's distance past c.a toward c.b
      const bool up = la->second.second;
      const planner::Vertex from = up ? c.a : c.b, to = up ? c.b : c.a;
      const double past = up ? frac : ai.spacing - frac;
      near_.push_back({from, false, past, to, i});
      near_.push_back({to, true, ai.spacing - past, from, i});
    } else if (following_) {
      near_.push_back({c.a, false, 0.0, -1, i});
    }
    // The body on its lane: [front - length, front].
    bodies_.push_back({2 * la->second.first + la->second.second, poses[i].pos - length_, poses[i].pos, i});
  }
  if (following_) check_following(poses, ids, when, group);
  std::sort(bodies_.begin(), bodies_.end(), [](const Body& x, const Body& y) {
    return x.lane != y.lane ? x.lane < y.lane : x.back < y.back;
  });
  size_t far = 0;  // on the current lane, the body reaching furthest so far
  for (size_t k = 1; k < bodies_.size(); ++k) {
    if (bodies_[k].lane != bodies_[far].lane) {
      far = k;
      continue;
    }
    if (bodies_[k].back < bodies_[far].front - 1e-9)
      throw ControlError(when + std::string("AGVs ") + ids[bodies_[far].agent] + " and " + ids[bodies_[k].agent] +
                         " overlap on lane " + poses[bodies_[k].agent].lane + " (bodies intersect)");
    if (bodies_[k].front > bodies_[far].front) far = k;
  }
}

void Safety::check_following(const std::vector<VehiclePose>& poses, const std::vector<std::string>& ids,
                              const std::string& when, const std::vector<int>& group)
{
  auto group_of = [&](int i) { return static_cast<size_t>(i) < group.size() ? group[i] : -1; };
  std::sort(near_.begin(), near_.end(), [](const Near& x, const Near& y) { return x.cell < y.cell; });
  auto fail = [&](const Near& x, const Near& y, const std::string& what) {
    last_overlap_ = {x.agent, y.agent};
    throw ControlError(when + "AGVs " + ids[x.agent] + " and " + ids[y.agent] + " " + what + " at cell " +
                       std::to_string(x.cell) + " (" + poses[x.agent].lane + " " + std::to_string(poses[x.agent].pos) +
                       ", " + poses[y.agent].lane + " " + std::to_string(poses[y.agent].pos) + ")");
  };
  for (size_t lo = 0; lo < near_.size();) {
    size_t hi = lo + 1;
    while (hi < near_.size() && near_[hi].cell == near_[lo].cell) ++hi;
    for (size_t x = lo; x < hi; ++x)
      for (size_t y = x + 1; y < hi; ++y) {
        const Near& p = near_[x];
        const Near& q = near_[y];
        if (p.agent == q.agent) continue;
        if (group_of(p.agent) >= 0 && group_of(p.agent) == group_of(q.agent)) continue;
        // Both on one line through v (entering: behind v, else past it): bodies
        // [x - length, x] must not intersect.
        const double xp = p.entering ? -p.dist : p.dist, xq = q.entering ? -q.dist : q.dist;
        if (p.entering != q.entering) {
          const Near& in = p.entering ? p : q;
          const Near& out = p.entering ? q : p;
          if (out.other >= 0 && out.other == in.other) fail(p, q, "pass head-on");
        }
        if (std::fabs(xp - xq) < length_ - 1e-9) fail(p, q, "overlap (bodies intersect)");
      }
    lo = hi;
  }
}

}  // namespace controller
