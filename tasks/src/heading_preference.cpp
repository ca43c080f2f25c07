#include "tasks/heading_preference.hpp"

#include "tasks/action_model.hpp"

namespace tasks {

HeadingPreference::HeadingPreference(const planner::Graph& g, const planner::Config& starts)
    : g_(g), dist_(g), at_(starts), heading_(starts.size(), 0)
{
}

float HeadingPreference::score(int agent, planner::Vertex from, planner::Vertex to, planner::Rng& rng)
{
  float s = static_cast<float>(dist_.get(agent, to)) + 0.3f * static_cast<float>(rng.uniform());
  if (to != from && from == at_[agent]) {
    const int turns = (heading_of_move(g_, from, to) - heading_[agent] + 4) % 4;
    s += 0.3f * static_cast<float>(turns == 3 ? 1 : turns);  // quarter turns: 0, 1 or 2
  }
  return s;
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
