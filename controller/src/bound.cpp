#include "controller/bound.hpp"

#include <cmath>

#include "planner/heading.hpp"

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
  AloneBound b(&map, k);
  for (const planner::Config& c : plan) b.add(c);
  return b.result();
}

std::vector<double> alone_moves(const std::vector<planner::Config>& plan)
{
  AloneBound b(nullptr, {});
  for (const planner::Config& c : plan) b.add(c);
  return b.result();
}

void AloneBound::count_turns(const planner::Graph& g, std::vector<int> start_headings, double turn_s)
{
  turns_on_ = &g;
  heading_ = std::move(start_headings);
  turn_s_ = turn_s;
}

void AloneBound::add(const planner::Config& c)
{
  if (last_.empty()) {
    last_ = before_ = c;
    stretch_.assign(c.size(), 0.0);
    t_.assign(c.size(), 0.0);
    return;
  }
  for (size_t i = 0; i < c.size(); ++i) {
    const planner::Vertex v = c[i];
    if (v == last_[i]) continue;
    if (!map_) {
      t_[i] += 1;
      if (turns_on_) {
        const int h = planner::heading_of_move(*turns_on_, last_[i], v);
        t_[i] += planner::quarter_turns(heading_[i], h);
        heading_[i] = h;
      }
    } else if (turns_on_) {
      const int h = planner::heading_of_move(*turns_on_, last_[i], v);
      if (const int q = planner::quarter_turns(heading_[i], h); q > 0) {  // rest, a step at rest, turn
        t_[i] += rest_to_rest_s(stretch_[i], k_) + k_.dt + q * turn_s_;
        stretch_[i] = 0;
      }
      heading_[i] = h;
      const gridify::Cell &a = map_->cells[last_[i]], &b = map_->cells[v];
      stretch_[i] += std::hypot(b.x - a.x, b.y - a.y);
    } else {
      if (v == before_[i] && before_[i] != last_[i]) {  // reverses: rest, turn in place (one step)
        t_[i] += rest_to_rest_s(stretch_[i], k_) + k_.dt;
        stretch_[i] = 0;
      }
      const gridify::Cell &a = map_->cells[last_[i]], &b = map_->cells[v];
      stretch_[i] += std::hypot(b.x - a.x, b.y - a.y);
    }
    before_[i] = last_[i];
    last_[i] = v;
  }
}

std::vector<double> AloneBound::result() const
{
  std::vector<double> out = t_;
  if (map_)
    for (size_t i = 0; i < out.size(); ++i) out[i] += rest_to_rest_s(stretch_[i], k_);
  return out;
}

}  // namespace controller
