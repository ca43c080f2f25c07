#include "policy/observation.hpp"

#include <algorithm>
#include <stdexcept>

namespace policy {

using planner::Vertex;

ObservationBuilder::ObservationBuilder(const planner::Graph& g, ObservationSpec spec)
    : g_(g), spec_(spec), dist_(g), occ_(static_cast<size_t>(g.size()), -1)
{
  if (!g.is_grid()) throw std::invalid_argument("policy observations need a grid graph");
  if (spec.radius < 1) throw std::invalid_argument("observation radius must be >= 1");
}

void ObservationBuilder::set_goals(const planner::Config& goals)
{
  goals_ = goals;
  dist_.set_goals(goals);
}

void ObservationBuilder::build(const Vertex* config, int n, float* out)
{
  if (n != static_cast<int>(goals_.size()))
    throw std::logic_error("ObservationBuilder::build: " + std::to_string(n) + " agents but " +
                           std::to_string(goals_.size()) + " goals");
  const int r = spec_.radius, W = spec_.window(), area = W * W;
  const float scale = static_cast<float>(2 * r);
  std::fill(out, out + static_cast<size_t>(n) * spec_.size(), 0.0f);
  for (int i = 0; i < n; ++i) occ_[config[i]] = i;

  for (int i = 0; i < n; ++i) {
    float* o = out + static_cast<size_t>(i) * spec_.size();
    const Vertex v = config[i];
    const int ax = g_.cell_x(v), ay = g_.cell_y(v);
    const int32_t d0 = dist_.get(i, v);
    for (int wy = 0; wy < W; ++wy) {
      for (int wx = 0; wx < W; ++wx) {
        const int k = wy * W + wx;
        const Vertex u = g_.at(ax + wx - r, ay + wy - r);  // -1 off the map or blocked
        if (u < 0) {
          o[kObstacle * area + k] = 1.0f;
          o[kGoalDistance * area + k] = 1.0f;
          continue;
        }
        const int32_t j = occ_[u];
        if (j >= 0 && j != i) {
          o[kAgent * area + k] = 1.0f;
          if (goals_[j] == u) o[kParked * area + k] = 1.0f;
        }
        const int32_t d = dist_.get(i, u);
        o[kGoalDistance * area + k] =
            d >= planner::DistTable::kInf ? 1.0f : static_cast<float>(std::clamp(d - d0, -2 * r, 2 * r)) / scale;
      }
    }
  }
  for (int i = 0; i < n; ++i) occ_[config[i]] = -1;
}

}  // namespace policy
