#pragma once
// ActionPreference: the order in which PIBT tries an agent's candidate moves (its
// neighbours and staying put). PIBT sorts candidates by ascending score. Without a
// preference PIBT uses distance-to-goal plus a uniform [0,1) random tie-break; plugging a
// learned one-step policy in here gives collision-shield PIBT (CS-PIBT): the policy
// proposes, PIBT (with LaCAM's constraints) guarantees a collision-free configuration.
#include "planner/config.hpp"
#include "planner/graph.hpp"
#include "planner/rng.hpp"

namespace planner {

class ActionPreference {
 public:
  virtual ~ActionPreference() = default;

  // The planner's goals changed (construction, a lifelong epoch). Preferences that look
  // at goals themselves (a learned policy's observations) update here.
  virtual void set_goals(const Config& goals) { (void)goals; }

  // Called once before PIBT generates a successor of `config` (n agents): the place
  // for batched inference over all agents.
  virtual void prepare(const Vertex* config, int n) { (void)config, (void)n; }

  // Score of agent `agent` moving from `from` to `to` (`to` == `from` means stay);
  // lower is tried first. `rng` is the planner's, for tie-breaks.
  virtual float score(int agent, Vertex from, Vertex to, Rng& rng) = 0;
};

}  // namespace planner
