#pragma once
// Helpers of the closed-loop tests: stops injected from outside the controller (a second
// client acting on SUMO in the same step, as a person or a pallet in the aisle would), and
// the AGVs' kinematics read back from SUMO's own fcd output.
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "controller/controller.hpp"
#include "controller_test_util.hpp"

namespace ctest_util {

// Stops of `min_s`..`max_s` seconds on every `every`-th AGV, one after a pause of 3-15 s,
// braked at `decel` (the AGV's own safety brake) and held at 0 while they last.
struct OutsideStops {
  std::map<int, std::vector<std::pair<double, double>>> windows;  // agent -> [from, to) s
  double decel = 1, dt = 0.125;
  long long steps_held = 0;

  OutsideStops(int agents, int every, double min_s, double max_s, double decel_, double dt_, unsigned seed,
               double horizon_s = 2000)
      : decel(decel_), dt(dt_)
  {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> pause(3, 15), len(min_s, max_s);
    for (int a = 0; a < agents; a += every)
      for (double t = pause(rng); t < horizon_s; t += pause(rng)) {
        const double l = len(rng);
        windows[a].push_back({t, t + l});
        t += l;
      }
  }
  void attach(controller::Controller& c)
  {
    c.on_step = [this](controller::SumoBackend& sumo, const std::vector<controller::VehiclePose>& poses) {
      if (poses.empty()) return;
      const double t = sumo.time();
      for (const auto& [a, w] : windows)
        for (const auto& [from, to] : w)
          if (t >= from && t < to) {
            sumo.set_speed("agv" + std::to_string(a), std::max(0.0, poses[a].speed - decel * dt));
            ++steps_held;
            break;
          }
    };
  }
};

// Per vehicle, from fcd.xml: the largest speed, acceleration and deceleration between two
// consecutive timesteps, and its speed in the last timestep.
struct Kinematics {
  double max_speed = 0, max_accel = 0, max_decel = 0;
  std::map<std::string, double> last_speed;
  double last_time = 0;
};

// Calls f(time, block) for every <timestep> of an fcd.xml, `block` its text (vehicles).
template <class F>
void for_each_fcd_step(const std::string& fcd, F f)
{
  const std::string s = slurp(fcd);
  const std::regex step_re(R"re(<timestep time="([-0-9.e]+)")re");
  double t = 0;
  size_t pos = 0;
  while (pos < s.size()) {
    const size_t a = s.find("<timestep", pos);
    if (a == std::string::npos) break;
    size_t b = s.find("<timestep", a + 1);
    if (b == std::string::npos) b = s.size();
    const std::string block = s.substr(a, b - a);
    std::smatch m;
    if (std::regex_search(block, m, step_re)) t = std::stod(m[1]);
    f(t, block);
    pos = b;
  }
}

inline Kinematics fcd_kinematics(const std::string& fcd, double dt)
{
  Kinematics k;
  const std::regex veh_re(R"re(<vehicle id="([^"]+)"[^>]* speed="([-0-9.e]+)")re");
  std::map<std::string, std::pair<double, double>> prev;  // id -> (time, speed)
  for_each_fcd_step(fcd, [&](double t, const std::string& block) {
    k.last_time = t;
    k.last_speed.clear();
    for (auto it = std::sregex_iterator(block.begin(), block.end(), veh_re); it != std::sregex_iterator(); ++it) {
      const std::string id = (*it)[1];
      const double v = std::stod((*it)[2]);
      k.max_speed = std::max(k.max_speed, v);
      auto p = prev.find(id);
      if (p != prev.end() && std::abs(t - p->second.first - dt) < 1e-6) {
        k.max_accel = std::max(k.max_accel, (v - p->second.second) / dt);
        k.max_decel = std::max(k.max_decel, (p->second.second - v) / dt);
      }
      prev[id] = {t, v};
      k.last_speed[id] = v;
    }
  });
  return k;
}

// Per vehicle, from fcd.xml: (time, lane, front position on the lane).
struct FcdPose {
  double t = 0;
  std::string lane;
  double pos = 0;
};
inline std::map<std::string, std::vector<FcdPose>> fcd_poses(const std::string& fcd)
{
  std::map<std::string, std::vector<FcdPose>> out;
  const std::regex veh_re(R"re(<vehicle id="([^"]+)"[^>]* pos="([-0-9.e]+)" lane="([^"]+)")re");
  for_each_fcd_step(fcd, [&](double t, const std::string& block) {
    for (auto it = std::sregex_iterator(block.begin(), block.end(), veh_re); it != std::sregex_iterator(); ++it)
      out[(*it)[1]].push_back({t, (*it)[3], std::stod((*it)[2])});
  });
  return out;
}

}  // namespace ctest_util
