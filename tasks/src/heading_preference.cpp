#include "tasks/heading_preference.hpp"

#include <algorithm>

#include "tasks/action_model.hpp"

namespace tasks {

using planner::quarter_turns;

HeadingPreference::HeadingPreference(const planner::Graph& g, const planner::Config& starts, HeadingCost cost)
    : g_(g), dist_(g), cost_(cost), at_(starts), heading_(starts.size(), 0)
{
}

int32_t HeadingPreference::cost_to_go(int agent, planner::Vertex v, int heading)
{
  const int32_t d = dist_.get(agent, v);
  if (d == 0 || d >= planner::DistTable::kInf) return d;
  int turns = 2;
  for (planner::Vertex w : g_.neighbors(v))
    if (dist_.get(agent, w) < d) turns = std::min(turns, quarter_turns(heading, heading_of_move(g_, v, w)));
  return d + turns;
}

float HeadingPreference::score(int agent, planner::Vertex from, planner::Vertex to, planner::Rng& rng)
{
  const float noise = static_cast<float>(rng.uniform());
  if (cost_ == HeadingCost::Ties) {
    float s = static_cast<float>(dist_.get(agent, to)) + 0.3f * noise;
    if (to != from && from == at_[agent])
      s += 0.3f * static_cast<float>(quarter_turns(heading_[agent], heading_of_move(g_, from, to)));
    return s;
  }
  if (from != at_[agent]) return static_cast<float>(dist_.get(agent, to)) + noise;  // heading unknown
  // Rotation-aware cost in steps; the noise (< 1) only breaks ties.
  if (to == from) return static_cast<float>(1 + cost_to_go(agent, from, heading_[agent])) + 0.9f * noise;
  const int h = heading_of_move(g_, from, to);
  return static_cast<float>(quarter_turns(heading_[agent], h) + 1 + cost_to_go(agent, to, h)) + 0.9f * noise;
}

void HeadingPreference::prepare(const planner::Vertex* config, int n)
{
  if (cost_ != HeadingCost::Turns) return;
  for (int i = 0; i < n && i < static_cast<int>(at_.size()); ++i) {
    if (config[i] != at_[i]) continue;  // no heading known: plain distances
    for (planner::Vertex u : g_.neighbors(config[i]))
      for (planner::Vertex w : g_.neighbors(u))
        if (w != config[i]) dist_.prefetch(i, w);
  }
}

void HeadingPreference::committed(const planner::Config& next)
{
  for (size_t i = 0; i < next.size(); ++i)
    if (next[i] != at_[i]) {
      heading_[i] = heading_of_move(g_, at_[i], next[i]);
      at_[i] = next[i];
    }
}

}  // namespace tasks
