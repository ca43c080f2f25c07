#pragma once
// DelayModel: what makes real AGVs late, reproducible by seed. Time is counted in the
// executor's update periods ("ticks": one MAPF tick in rtlacam-lifelong, one controller
// tick in SUMO); callers convert seconds to ticks.
//
//   stops      : per agent per tick, a stop starts with probability `p` (Bernoulli, as
//                LoRR Start-Kit v3's delay model), or Poisson events at `rate` per agent
//                per tick (P(start) = 1 - exp(-rate)); it lasts a uniform number of ticks in
//                [min_ticks, max_ticks]. Only agents not already stopped can start one.
//   fraction   : only this share of the agents (chosen by seed) ever stops (1 = all).
//   slowdowns  : agent -> speed factor in (0, 1]: it needs ceil(1 / f) ticks per move on a
//                MAPF graph; SUMO scales its speed by f.
//   stuck      : agent, first tick, ticks: a stop at a fixed time (a blocked AGV).
// A stopped agent makes no progress (it stays put). Everything here is validated by
// check(); the YAML reader and rtlacam-lifelong turn its message into their one-line error.
#include <cstdint>
#include <string>
#include <vector>

#include "planner/rng.hpp"

namespace executor {

struct Stuck {
  int agent = 0;
  long long at = 0;    // first stopped tick
  long long ticks = 0;
};

struct Slowdown {
  int agent = 0;
  double factor = 1;   // (0, 1]
};

struct DelaySpec {
  std::string kind = "none";  // none | bernoulli | poisson
  double p = 0;               // bernoulli: [0, 1]
  double rate = 0;            // poisson: events per agent per tick, >= 0
  long long min_ticks = 1, max_ticks = 1;  // stop length, 1 <= min <= max
  double fraction = 1;        // (0, 1]
  std::vector<Slowdown> slow;
  std::vector<Stuck> stuck;
  uint64_t seed = 0;
};

// "" if the spec is usable for n agents, else "<key>: what is wrong" (key as in the YAML).
std::string check(const DelaySpec& s, int n);

class DelayModel {
 public:
  DelayModel(const DelaySpec& s, int n);

  // Draws the stops of tick t (call once per tick, t = 0, 1, ...).
  void tick(long long t);
  bool stopped(int agent) const { return left_[agent] > 0; }
  double factor(int agent) const { return factor_[agent]; }
  // Ticks a move takes at this agent's speed: ceil(1 / factor).
  int move_ticks(int agent) const;
  long long stop_ticks() const { return stop_ticks_; }  // agent-ticks stopped so far
  long long stops() const { return stops_; }           // stops started so far

 private:
  DelaySpec s_;
  planner::Rng rng_;
  std::vector<long long> left_;  // ticks of the current stop left (after this tick's draw)
  std::vector<double> factor_;
  std::vector<char> eligible_;
  double p_start_ = 0;
  long long stop_ticks_ = 0, stops_ = 0;
};

}  // namespace executor
