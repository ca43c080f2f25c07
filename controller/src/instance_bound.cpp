#include "controller/instance_bound.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

#include "planner/heading.hpp"

namespace controller {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The least cost from `s` to `goal` (any heading there); arc(u, v) >= 0 prices a move,
// turn(q) q quarter turns. headings: states are (cell, heading), else cells. Stops at the
// goal; kInf if it cannot be reached.
double least(const planner::Graph& g, planner::Vertex s, planner::Vertex goal, int heading,
             const std::function<double(planner::Vertex, planner::Vertex)>& arc, double turn_cost)
{
  const bool rot = heading >= 0;
  const int n = rot ? 4 : 1;
  std::vector<double> d(static_cast<size_t>(g.size()) * n, kInf);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
  const int s0 = s * n + (rot ? heading : 0);
  d[s0] = 0;
  q.push({0.0, s0});
  while (!q.empty()) {
    const auto [c, x] = q.top();
    q.pop();
    if (c > d[x]) continue;
    const planner::Vertex u = x / n;
    if (u == goal) return c;
    for (planner::Vertex v : g.neighbors(u)) {
      double cv = c + arc(u, v);
      int y = v * n;
      if (rot) {
        const int h = planner::heading_of_move(g, u, v);
        cv += planner::quarter_turns(x % n, h) * turn_cost;
        y += h;
      }
      if (cv < d[y]) {
        d[y] = cv;
        q.push({cv, y});
      }
    }
  }
  return kInf;
}

double finite(double x) { return std::isfinite(x) ? x : 0.0; }  // unreachable: no bound

}  // namespace

std::vector<double> lockstep_alone_ticks(const planner::Graph& g, const planner::Config& starts, const planner::Config& goals,
                                         const std::vector<int>& start_headings)
{
  std::vector<double> out(starts.size());
  auto move = [](planner::Vertex, planner::Vertex) { return 1.0; };
  for (size_t i = 0; i < starts.size(); ++i)
    out[i] = finite(least(g, starts[i], goals[i], start_headings.empty() ? -1 : start_headings[i], move, 1.0));
  return out;
}

std::vector<double> physical_alone_s(const gridify::CellMap& map, const planner::Config& starts, const planner::Config& goals,
                                     const Kinematics& k, const std::vector<double>& cell_speed,
                                     const std::vector<int>& start_headings, double turn_step_s)
{
  const planner::Graph& g = map.graph;
  auto metres = [&](planner::Vertex u, planner::Vertex v) {
    const gridify::Cell &a = map.cells[u], &b = map.cells[v];
    return std::hypot(b.x - a.x, b.y - a.y);
  };
  // The cruise walk only matters where some lane is slower than the vType.
  const bool slow = std::any_of(cell_speed.begin(), cell_speed.end(), [&](double s) { return s < k.max_speed; });
  auto cruise = [&](planner::Vertex u, planner::Vertex v) {
    const double top = std::min(k.max_speed, std::max(cell_speed[u], cell_speed[v]));
    return top > 0 ? metres(u, v) / top : kInf;
  };
  auto none = [](planner::Vertex, planner::Vertex) { return 0.0; };
  std::vector<double> out(starts.size());
  for (size_t i = 0; i < starts.size(); ++i) {
    double drive = rest_to_rest_s(finite(least(g, starts[i], goals[i], -1, metres, 0)), k);
    if (slow) drive = std::max(drive, finite(least(g, starts[i], goals[i], -1, cruise, 0)));
    double turns = 0;
    if (!start_headings.empty() && turn_step_s > 0)
      turns = finite(least(g, starts[i], goals[i], start_headings[i], none, 1.0)) * turn_step_s;
    out[i] = drive + turns;
  }
  return out;
}

std::vector<double> fastest_cell_speeds(const gridify::CellMap& map, double top_speed)
{
  std::vector<double> v(map.cells.size(), top_speed);
  for (size_t c = 0; c < map.cells.size(); ++c) {
    if (map.cells[c].poses.empty()) continue;
    double s = 0;
    for (const gridify::SumoPose& p : map.cells[c].poses) {
      auto it = map.lane_aisle.find(p.lane);
      if (it == map.lane_aisle.end()) {
        s = top_speed;  // a lane we do not know: no slower than the vType
        break;
      }
      const gridify::Aisle& a = map.aisles[static_cast<size_t>(it->second.first)];
      s = std::max(s, it->second.second ? a.speed_ab : a.speed_ba);
    }
    v[c] = std::min(s, top_speed);
  }
  return v;
}

}  // namespace controller
