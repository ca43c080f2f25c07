#include "planner/rotation_settings.hpp"

#include <stdexcept>

namespace planner {

RotationSettings RotationSettings::lifelong(Solver kind)
{
  RotationSettings s;
  s.guidance = kind == Solver::PibtRot || kind == Solver::Epibt ? "arrows" : "none";
  s.traffic_flow = kind == Solver::Epibt;
  return s;
}

const std::vector<std::string>& rotation_keys()
{
  static const std::vector<std::string> keys = {"back_last", "guidance",      "guidance_costs", "traffic_flow",
                                                "depth",     "lns_rounds",    "revisit",        "priority",
                                                "pocket_exit", "leavers_first", "window",       "neighbourhood"};
  return keys;
}

std::string rotation_key_misuse(Solver kind, const std::string& key)
{
  bool known = false;
  for (const std::string& k : rotation_keys()) known = known || k == key;
  if (!known) throw std::invalid_argument("unknown rotation key '" + key + "'");
  if (!plans_rotation(kind))
    return std::string("only with a rotation solver (pibt-rot | epibt | wppl), not ") + to_string(kind);
  // The keys one solver alone reads; the others are every rotation solver's but back_last.
  static const std::pair<const char*, Solver> only[] = {
      {"traffic_flow", Solver::Epibt}, {"depth", Solver::Epibt},         {"lns_rounds", Solver::Epibt},
      {"revisit", Solver::Epibt},      {"priority", Solver::Epibt},      {"leavers_first", Solver::Epibt},
      {"window", Solver::Wppl},        {"neighbourhood", Solver::Wppl}};
  for (const auto& [k, s] : only)
    if (key == k && kind != s) return std::string("only with solver ") + to_string(s) + ", not " + to_string(kind);
  if (key == "back_last" && kind == Solver::Epibt)
    return "only with solver pibt-rot or wppl (epibt's operations decide how a robot yields)";
  return "";
}

std::string check(const RotationSettings& s)
{
  auto range = [](const char* key, int v, int lo, int hi) {
    return v < lo || v > hi ? std::string(key) + ": must be in " + std::to_string(lo) + ".." + std::to_string(hi) +
                                  ", got " + std::to_string(v)
                            : std::string();
  };
  if (s.guidance != "none" && s.guidance != "arrows") return "guidance: must be none or arrows, not '" + s.guidance + "'";
  if (s.guidance == "arrows")
    for (size_t i = 0; i < 3; ++i) {
      const std::string key = "guidance_costs[" + std::to_string(i) + "]";
      if (std::string e = range(key.c_str(), s.guidance_costs[i], 1, Guidance::kMaxCost); !e.empty()) return e;
    }
  if (s.priority != "distance" && s.priority != "age") return "priority: must be distance or age, not '" + s.priority + "'";
  for (const std::string& e : {range("depth", s.depth, 3, 5), range("lns_rounds", s.lns_rounds, -1, 1000000),
                               range("revisit", s.revisit, 1, 1000000), range("window", s.window, 1, 1000),
                               range("neighbourhood", s.neighbourhood, 1, 100000)})
    if (!e.empty()) return e;
  return "";
}

void apply(const RotationSettings& s, const Graph& g, SolverOptions& so)
{
  if (std::string e = check(s); !e.empty()) throw std::invalid_argument(e);
  so.back_last = s.back_last;
  so.pocket_exit = s.pocket_exit;
  so.guidance = Guidance{};
  if (s.guidance == "arrows") {
    try {
      so.guidance = arrow_guidance(g, s.guidance_costs[0], s.guidance_costs[1], s.guidance_costs[2]);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("guidance: ") + e.what());  // e.g. not a grid
    }
  }
  so.epibt.depth = s.depth;
  so.epibt.lns_rounds = s.lns_rounds;
  so.epibt.revisit = s.revisit;
  so.epibt.priority = s.priority == "age" ? EpibtOptions::Priority::Age : EpibtOptions::Priority::Distance;
  so.epibt.pocket_exit = s.pocket_exit;
  so.epibt.leavers_first = s.leavers_first;
  so.epibt.tf.on = s.traffic_flow;
  so.wppl.window = s.window;
  so.wppl.neighbourhood = s.neighbourhood;
}

}  // namespace planner
