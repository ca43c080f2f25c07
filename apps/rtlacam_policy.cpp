// rtlacam-policy: tools around the learned one-step policy.
//   dump  runs full-horizon LaCAM (with swap) on MovingAI instances and writes, for every
//         step of each solution and every agent, its observation and the expert's next
//         action (policy/dump_file.hpp) -- the training data of scripts/train_policy.py.
//   time  measures observation building and the batched forward pass for N agents.
#include <CLI/CLI.hpp>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "planner/error.hpp"
#include "planner/lacam/lacam.hpp"
#include "planner/movingai.hpp"
#include "planner/rng.hpp"
#include "policy/actions.hpp"
#include "policy/dump_file.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"

using namespace planner;
using namespace policy;

namespace {

struct DumpArgs {
  std::string map_file, out_file;
  std::vector<std::string> scens;
  std::vector<int> agents;
  int radius = 4;
  double keep = 1.0, timeout_s = 10.0;
  uint64_t seed = 0;
};

int run_dump(const DumpArgs& a)
{
  const Graph g = load_map(a.map_file);
  ObservationSpec spec;
  spec.radius = a.radius;
  DumpWriter out(a.out_file, spec);
  ObservationBuilder builder(g, spec);
  Rng rng(a.seed);
  std::vector<float> obs;
  for (const std::string& scen : a.scens) {
    for (int n : a.agents) {
      const Instance ins = load_scen(scen, g, n);
      DistTable dist(g);
      LacamOptions opt;
      opt.seed = a.seed;
      Lacam lacam(g, dist, opt);
      lacam.reset(ins.starts, ins.goals);
      const auto t0 = Clock::now();
      const Status st = lacam.search(Budget::time_ms(a.timeout_s * 1000.0));
      nlohmann::json j{{"scen", scen}, {"agents", n}, {"status", to_string(st)}, {"search_ms", ms_since(t0)}};
      const uint64_t before = out.count();
      if (st == Status::Solved) {
        const std::vector<Config> path = lacam.path(lacam.goal_node());
        builder.set_goals(ins.goals);
        obs.resize(static_cast<size_t>(n) * spec.size());
        for (size_t t = 0; t + 1 < path.size(); ++t) {
          builder.build(path[t].data(), n, obs.data());
          const bool unfinished = path[t] != ins.goals;
          for (int i = 0; i < n; ++i) {
            if (a.keep < 1.0 && rng.uniform() >= a.keep) continue;
            const int act = action_of(g, path[t][i], path[t + 1][i]);
            const uint8_t flags = (path[t][i] == ins.goals[i] ? 1 : 0) | (unfinished ? 2 : 0);
            out.add(obs.data() + static_cast<size_t>(i) * spec.size(), act, flags);
          }
        }
        j["makespan"] = path.size() - 1;
      }
      j["samples"] = out.count() - before;
      std::cerr << j.dump() << std::endl;
    }
  }
  out.close();
  std::cout << nlohmann::json{{"out", a.out_file}, {"samples", out.count()}, {"radius", a.radius}}.dump() << std::endl;
  return 0;
}

struct TimeArgs {
  std::string weights, map_file, scen;
  int agents = 400, reps = 50;
};

// Times the work prepare() does per generated configuration, on the scenario's starts and
// then on random configurations (each rep moves the agents, so no result is cached).
int run_time(const TimeArgs& a)
{
  const Graph g = load_map(a.map_file);
  const Instance ins = load_scen(a.scen, g, a.agents);
  const Model m = load_weights(a.weights);
  PolicyPreference pref(g, m, ins.goals);
  Rng rng(0);
  Config c = ins.starts;
  pref.prepare(c.data(), a.agents);  // warm-up: BFS tables, allocations
  const double obs0 = pref.observation_ms(), fwd0 = pref.forward_ms();
  std::vector<int32_t> occ(static_cast<size_t>(g.size()), 0);
  for (Vertex v : c) occ[v] = 1;
  for (int r = 0; r < a.reps; ++r) {
    for (int i = 0; i < a.agents; ++i) {  // each agent tries one random neighbour
      const auto nb = g.neighbors(c[i]);
      if (nb.empty()) continue;  // an isolated cell (a 1x1 map): rng.below(0) is undefined
      const Vertex u = nb[rng.below(static_cast<uint32_t>(nb.size()))];
      if (!occ[u]) occ[c[i]] = 0, occ[u] = 1, c[i] = u;
    }
    pref.prepare(c.data(), a.agents);
  }
  const double obs_ms = (pref.observation_ms() - obs0) / a.reps, fwd_ms = (pref.forward_ms() - fwd0) / a.reps;
  nlohmann::json j{{"agents", a.agents},         {"reps", a.reps},
                   {"radius", m.spec.radius},    {"parameters", m.num_parameters()},
                   {"observation_ms", obs_ms},   {"forward_ms", fwd_ms},
                   {"total_ms", obs_ms + fwd_ms}, {"weights", a.weights}};
  std::cout << j.dump() << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Learned one-step MAPF policy: training-data dump and inference timing"};
  app.require_subcommand(1);

  DumpArgs d;
  CLI::App* dump = app.add_subcommand("dump", "write (observation, LaCAM expert action) pairs for training");
  dump->add_option("--map", d.map_file, "MovingAI .map file")->required();
  dump->add_option("--scen", d.scens, "MovingAI .scen files")->required();
  dump->add_option("--agents,-N", d.agents, "agent counts (each scen is run with each)")
      ->required()
      ->check(cli::positive());  // each count; -3 was a std::length_error (rc 1)
  dump->add_option("--out", d.out_file, "output dump file")->required();
  dump->add_option("--radius", d.radius, "observation window radius (window 2r+1)")
      ->check(CLI::Range(1, 32))
      ->capture_default_str();
  dump->add_option("--keep", d.keep, "fraction of (agent, step) samples kept, at random")
      ->check(cli::finite_range(0, 1))
      ->capture_default_str();
  dump->add_option("--timeout-s", d.timeout_s, "LaCAM time limit per instance (unsolved ones are skipped)")
      ->check(cli::finite_range(0, 1e7))
      ->capture_default_str();
  dump->add_option("--seed", d.seed, "seed of LaCAM and of the sampling")->capture_default_str();

  TimeArgs t;
  CLI::App* time = app.add_subcommand("time", "time observations + forward pass per planning step (JSON)");
  time->add_option("--weights", t.weights, "policy weights file")->required();
  time->add_option("--map", t.map_file, "MovingAI .map file")->required();
  time->add_option("--scen", t.scen, "MovingAI .scen file")->required();
  time->add_option("--agents,-N", t.agents, "number of agents")->check(cli::positive())->capture_default_str();
  time->add_option("--reps", t.reps, "timed configurations")->check(cli::positive())->capture_default_str();
  cli::add_version(app, "rtlacam-policy");
  RTLACAM_PARSE(app, argc, argv);

  try {
    if (*dump) return run_dump(d);
    return run_time(t);
  } catch (const InputError& e) {
    std::cerr << "rtlacam-policy: " << e.what() << std::endl;
    return cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "rtlacam-policy: error: " << e.what() << std::endl;
    return cli::kRuntimeError;
  }
}
