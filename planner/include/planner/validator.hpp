#pragma once
// Validator: checks an executed sequence of configurations C^0, C^1, ... :
//   - C^0 equals the starts (and, when required, the last one equals the goals),
//   - every agent waits or moves along a graph arc (on a directed graph, a one-way arc
//     only forwards: Graph::adjacent(from, to)),
//   - no vertex conflict (two agents on one vertex),
//   - no swap conflict (two agents exchanging vertices over one edge).
// It works step by step (executors feed it every move they make) or on a whole plan, and
// keeps two costs, named as lacam3 names them:
//  - sum_of_costs (standard SOC, what the paper and lacam3 report): each agent is charged
//    every step up to its last arrival at its goal, i.e. (last timestep it is off its goal) + 1,
//    0 for an agent that never leaves its goal, and every step so far for one off its goal
//    now. Parking on a goal and leaving it later costs the parked steps too;
//  - sum_of_loss: one per agent per step, except a step that starts and ends on its goal.
// Goal changes (set_goals) charge against the goals in force at each step.
#include <string>
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace planner {

class Validator {
 public:
  Validator(const Graph& g, const Config& starts, const Config& goals);

  // Checks the transition current() -> next and advances. Returns false (and keeps the
  // first error) on a violation; the sequence then stays invalid.
  bool step(const Config& next);
  // Goal changes (lifelong) only affect the cost accounting.
  void set_goals(const Config& goals) { goals_ = goals; }

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  const Config& current() const { return current_; }
  const Graph& graph() const { return g_; }
  long long steps() const { return steps_; }           // makespan
  long long sum_of_costs() const { return soc_ - off_now_; }  // standard (last arrival)
  long long sum_of_loss() const { return loss_; }

  // A transition check on its own: "" if valid, else what is wrong.
  static std::string check_transition(const Graph& g, const Config& from, const Config& to);

 private:
  std::string check(const Config& from, const Config& to);

  const Graph& g_;
  Config current_, goals_;
  // vertex -> agent arriving / leaving in the step being checked, valid where stamp == epoch
  std::vector<int32_t> to_agent_, from_agent_;
  std::vector<uint32_t> to_stamp_, from_stamp_;
  uint32_t epoch_ = 0;
  std::string error_;
  long long steps_ = 0, soc_ = 0, loss_ = 0;
  // Per agent: last timestep off its goal, -1 none; soc_ sums last_off_ + 1, which for the
  // off_now_ agents off their goal at the last step is one more than the steps so far.
  std::vector<long long> last_off_;
  long long off_now_ = 0;
};

// Whole plan: "" if `plan` is valid from `starts` (and ends at `goals` when
// `require_goals`), else the first violation with its timestep.
std::string validate_plan(const Graph& g, const Config& starts, const Config& goals, const std::vector<Config>& plan,
                          bool require_goals);

}  // namespace planner
