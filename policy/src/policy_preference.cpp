#include "policy/policy_preference.hpp"

#include <stdexcept>

#include "planner/budget.hpp"
#include "policy/actions.hpp"

namespace policy {

using planner::Vertex;

PolicyPreference::PolicyPreference(const planner::Graph& g, const Model& model, const planner::Config& goals)
    : g_(g), model_(model), obs_(g, model.spec)
{
  if (model.input_size() != model.spec.size() || model.output_size() != kNumActions)
    throw std::invalid_argument("PolicyPreference: model shape does not match its observation spec");
  set_goals(goals);
}

void PolicyPreference::set_goals(const planner::Config& goals)
{
  obs_.set_goals(goals);
  last_.clear();  // cached probabilities were for the old goals
}

void PolicyPreference::prepare(const Vertex* config, int n)
{
  // LaCAM often expands the same node several times in a row (one constraint each):
  // the observations, hence the probabilities, are the same.
  if (static_cast<int>(last_.size()) == n && planner::config_equal(last_.data(), config, n)) return;
  last_.assign(config, config + n);

  const auto t0 = planner::Clock::now();
  x_.resize(model_.input_size(), n);
  obs_.build(config, n, x_.data());
  const auto t1 = planner::Clock::now();
  model_.forward(x_, logits_);
  // Softmax per agent (column), shifted by the column max for stability.
  prob_ = (logits_.rowwise() - logits_.colwise().maxCoeff()).array().exp().matrix();
  prob_.array().rowwise() /= prob_.colwise().sum().array();
  observation_ms_ += std::chrono::duration<double, std::milli>(t1 - t0).count();
  forward_ms_ += planner::ms_since(t1);
  ++inferences_;
}

float PolicyPreference::score(int agent, Vertex from, Vertex to, planner::Rng& rng)
{
  const int a = action_of(g_, from, to);
  if (a < 0) throw std::logic_error("PolicyPreference: move between non-adjacent grid cells");
  return -prob_(a, agent) + 1e-6f * rng.uniform();
}

}  // namespace policy
