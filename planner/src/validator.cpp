#include "planner/validator.hpp"

#include <algorithm>

namespace planner {

Validator::Validator(const Graph& g, const Config& starts, const Config& goals)
    : g_(g), current_(starts), goals_(goals), to_agent_(g.size()), from_agent_(g.size()), to_stamp_(g.size(), 0),
      from_stamp_(g.size(), 0), last_off_(starts.size(), -1)
{
  for (size_t i = 0; i < starts.size() && i < goals.size(); ++i)
    if (starts[i] != goals[i]) last_off_[i] = 0, ++soc_, ++off_now_;
}

// O(N) per step with epoch-stamped vertex arrays: executors check every step they run.
std::string Validator::check(const Config& from, const Config& to)
{
  using std::to_string;
  if (from.size() != to.size())
    return "configuration has " + to_string(to.size()) + " agents, expected " + to_string(from.size());
  const int n = static_cast<int>(from.size());
  if (++epoch_ == 0) {  // wrapped: forget old stamps
    std::fill(to_stamp_.begin(), to_stamp_.end(), 0);
    std::fill(from_stamp_.begin(), from_stamp_.end(), 0);
    epoch_ = 1;
  }
  for (int i = 0; i < n; ++i) {
    const Vertex u = from[i], v = to[i];
    if (v < 0 || v >= g_.size()) return "agent " + to_string(i) + " at vertex " + to_string(v) + ", not in the graph";
    if (u != v && !g_.adjacent(u, v))
      return "agent " + to_string(i) + " jumps from vertex " + to_string(u) + " to " + to_string(v) + " (not adjacent)";
    if (to_stamp_[v] == epoch_)
      return "vertex conflict: agents " + to_string(to_agent_[v]) + " and " + to_string(i) + " at vertex " + to_string(v);
    to_stamp_[v] = epoch_, to_agent_[v] = i;
    from_stamp_[u] = epoch_, from_agent_[u] = i;
  }
  for (int i = 0; i < n; ++i) {
    const Vertex u = from[i], v = to[i];
    if (u == v || from_stamp_[v] != epoch_) continue;
    const int j = from_agent_[v];
    if (to[j] == u)
      return "swap conflict: agents " + to_string(i) + " and " + to_string(j) + " exchange vertices " + to_string(u) +
             " and " + to_string(v);
  }
  return "";
}

std::string Validator::check_transition(const Graph& g, const Config& from, const Config& to)
{
  Validator v(g, from, from);
  return v.check(from, to);
}

bool Validator::step(const Config& next)
{
  if (!ok()) return false;
  std::string e = check(current_, next);
  if (!e.empty()) {
    error_ = "step " + std::to_string(steps_) + " -> " + std::to_string(steps_ + 1) + ": " + e;
    return false;
  }
  ++steps_;
  if (last_off_.size() < next.size()) last_off_.resize(next.size(), -1);
  off_now_ = 0;
  for (size_t i = 0; i < next.size(); ++i) {
    const bool on = i < goals_.size() && next[i] == goals_[i];
    if (!(on && current_[i] == next[i])) ++loss_;
    if (!on) {  // off its goal at steps_: charged every step up to here
      soc_ += steps_ - last_off_[i];
      last_off_[i] = steps_;
      ++off_now_;
    }
  }
  current_ = next;
  return true;
}

std::string validate_plan(const Graph& g, const Config& starts, const Config& goals, const std::vector<Config>& plan,
                          bool require_goals)
{
  if (plan.empty()) return "empty plan";
  if (plan.front() != starts) return "timestep 0 differs from the starts";
  Config sorted = starts;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return "vertex conflict at timestep 0";
  Validator v(g, starts, goals);
  for (size_t t = 1; t < plan.size(); ++t)
    if (!v.step(plan[t])) return v.error();
  if (require_goals && plan.back() != goals)
    return "last configuration (timestep " + std::to_string(plan.size() - 1) + ") is not the goals";
  return "";
}

}  // namespace planner
