#pragma once
// PolicyPreference: a learned one-step policy as PIBT's move order -- collision-shield
// PIBT (CS-PIBT; Veerapaneni et al., ICAPS 2024). Once per generated configuration,
// prepare() builds every agent's observation and runs the network batched over all agents;
// score() then ranks an agent's candidate moves by the predicted probability of the
// matching action (higher first). PIBT tries them in that order and its collision shield
// (vertex/swap checks, priority inheritance, LaCAM's constraints) keeps the configuration
// valid, so a bad prediction costs quality, never safety -- and under LaCAM or RT-LaCAM,
// never completeness either.
//
// As in CS-PIBT: moves into obstacles or off the map are not PIBT candidates at all, so
// their probability mass is simply ignored (the order of the rest is that of the
// renormalised distribution); probabilities closer than 1e-6 count as ties, broken by the
// planner's random number generator.
//
// Goals: the preference computes its own observations from the goals. Planners call
// set_goals() whenever theirs change (construction, lifelong epochs).
#include <Eigen/Core>

#include "planner/action_preference.hpp"
#include "policy/model.hpp"
#include "policy/observation.hpp"

namespace policy {

class PolicyPreference : public planner::ActionPreference {
 public:
  // `g` (a grid graph) and `model` must outlive this.
  PolicyPreference(const planner::Graph& g, const Model& model, const planner::Config& goals);

  void set_goals(const planner::Config& goals) override;

  void prepare(const planner::Vertex* config, int n) override;
  float score(int agent, planner::Vertex from, planner::Vertex to, planner::Rng& rng) override;

  // Action probabilities of the last prepared configuration: kNumActions x n.
  const Eigen::MatrixXf& probabilities() const { return prob_; }

  // Statistics: configurations inferred (a repeated configuration is served from the
  // last result) and the time spent building observations and in the network.
  long long inferences() const { return inferences_; }
  double observation_ms() const { return observation_ms_; }
  double forward_ms() const { return forward_ms_; }

 private:
  const planner::Graph& g_;
  const Model& model_;
  ObservationBuilder obs_;
  Eigen::MatrixXf x_, logits_, prob_;
  planner::Config last_;  // the configuration prob_ belongs to
  long long inferences_ = 0;
  double observation_ms_ = 0, forward_ms_ = 0;
};

}  // namespace policy
