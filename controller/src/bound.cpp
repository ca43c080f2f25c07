#include "controller/bound.hpp"

#include <cmath>

namespace controller {

double rest_to_rest_s(double L, const Kinematics& k)
{
  if (L <= 0) return 0;
  const double a = k.accel, d = k.decel, V = k.max_speed;
  const double ramps = V * V / (2 * a) + V * V / (2 * d);
  if (L >= ramps) return L / V + V / (2 * a) + V / (2 * d);
  const double peak = std::sqrt(2 * L * a * d / (a + d));  // a triangle: never reaches V
  return peak / a + peak / d;
}

std::vector<double> alone_s(const gridify::CellMap& map, const std::vector<planner::Config>& plan, const Kinematics& k)
{
  if (plan.empty()) return {};
  std::vector<double> out(plan.front().size(), 0.0);
  for (size_t i = 0; i < out.size(); ++i) {
    std::vector<planner::Vertex> path{plan.front()[i]};
    for (const planner::Config& c : plan)
      if (c[i] != path.back()) path.push_back(c[i]);
    double stretch = 0, t = 0;
    for (size_t s = 1; s < path.size(); ++s) {
      const gridify::Cell &u = map.cells[path[s - 1]], &v = map.cells[path[s]];
      if (s >= 2 && path[s] == path[s - 2]) {  // reverses: rest, turn in place (one step)
        t += rest_to_rest_s(stretch, k) + k.dt;
        stretch = 0;
      }
      stretch += std::hypot(v.x - u.x, v.y - u.y);
    }
    out[i] = t + rest_to_rest_s(stretch, k);
  }
  return out;
}

std::vector<double> alone_moves(const std::vector<planner::Config>& plan)
{
  if (plan.empty()) return {};
  std::vector<double> out(plan.front().size(), 0.0);
  for (size_t s = 1; s < plan.size(); ++s)
    for (size_t i = 0; i < out.size(); ++i) out[i] += plan[s][i] != plan[s - 1][i];
  return out;
}

}  // namespace controller
