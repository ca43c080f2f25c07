#include "ggo/lane_guidance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ggo {

namespace {
uint16_t clamp_cost(double c)
{
  if (!std::isfinite(c)) c = planner::Guidance::kMaxCost;  // exp overflow: the dearest
  return static_cast<uint16_t>(std::clamp<double>(std::lround(std::min(c, 1e6)), 1, planner::Guidance::kMaxCost));
}
}  // namespace

LaneGuidance::LaneGuidance(const planner::Graph& g, int unit_) : unit(unit_)
{
  if (!g.is_grid()) throw std::invalid_argument("lane guidance needs a grid graph");
  if (unit < 1 || unit * 3 > planner::Guidance::kMaxCost) throw std::invalid_argument("lane guidance unit out of range");
  for (planner::Vertex v = 0; v < g.size(); ++v) {
    width = std::max(width, g.cell_x(v) + 1);
    height = std::max(height, g.cell_y(v) + 1);
  }
  base = planner::arrow_guidance(g, 1, 3, 1);
}

int LaneGuidance::index(int x, int y, int o) const
{
  switch (o) {
    case 0: return 2 * y;
    case 2: return 2 * y + 1;
    case 1: return 2 * height + 2 * x;
    default: return 2 * height + 2 * x + 1;
  }
}

planner::Guidance LaneGuidance::to_guidance(const planner::Graph& g, const Eigen::VectorXd& p) const
{
  if (p.size() != dims()) throw std::invalid_argument("lane guidance: expected " + std::to_string(dims()) + " parameters");
  planner::Guidance gd;
  gd.turn = clamp_cost(unit * base.turn * std::exp(p[turn_index()]));
  gd.forward.resize(static_cast<size_t>(g.size()) * 4);
  for (planner::Vertex v = 0; v < g.size(); ++v)
    for (int o = 0; o < 4; ++o)
      gd.forward[static_cast<size_t>(v) * 4 + o] =
          clamp_cost(unit * base.forward_cost(v, o) * std::exp(p[index(g.cell_x(v), g.cell_y(v), o)]));
  return gd;
}

}  // namespace ggo
