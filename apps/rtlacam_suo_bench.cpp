// rtlacam-suo-bench: the CPU cost of SUO (Scatter, scatter.hpp) alone on one MovingAI
// instance, from the starts, distance tables computed beforehand (as they mostly are when
// RT-LaCAM* starts SUO). Prints one JSON line: thread CPU ms of each pass, collisions, and a
// hash of the published paths (equal hashes: the same paths, e.g. before/after a speed-up).
// Work is done in slices of --slice work units, as the planner resumes it.
#include <CLI/CLI.hpp>
#include <ctime>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "planner/movingai.hpp"
#include "planner/lacam/scatter.hpp"

using namespace planner;

namespace {
double cpu_ms()
{
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"SUO (scatter) CPU cost on a MovingAI instance"};
  std::string map_file, scen_file;
  int agents = 0, margin = 10, max_passes = 0, reps = 1;
  uint64_t seed = 0, slice = 4096;
  app.add_option("--map", map_file, "MovingAI .map")->required();
  app.add_option("--scen", scen_file, "MovingAI .scen")->required();
  app.add_option("-N,--agents", agents, "number of agents")->required();
  app.add_option("--margin", margin, "SUO: extra path length allowed per agent")->capture_default_str();
  app.add_option("--max-passes", max_passes, "passes at most (0: until collisions stop dropping)")->capture_default_str();
  app.add_option("--seed", seed, "random seed")->capture_default_str();
  app.add_option("--slice", slice, "work units per step() call")->capture_default_str();
  bool heap = false;
  app.add_flag("--heap", heap, "binary-heap open list (the earlier code) instead of the bucket queue");
  app.add_option("--reps", reps, "repetitions (the pass times are the minimum over them)")->capture_default_str();
  cli::add_version(app, "rtlacam-suo-bench");
  RTLACAM_PARSE(app, argc, argv);
  try {
    const Graph g = load_map(map_file);
    const Instance ins = load_scen(scen_file, g, agents);
    DistTable d(g);
    d.set_goals(ins.goals);
    for (int i = 0; i < agents; ++i)
      for (Vertex v = 0; v < static_cast<Vertex>(g.size()); ++v) d.get(i, v);
    std::vector<double> best;
    int64_t collisions = 0;
    uint64_t hash = 1469598103934665603ull;
    int passes = 0;
    uint64_t work = 0;  // Scatter's work units (4 per A* pop + path cells), all passes
    for (int r = 0; r < reps; ++r) {
      Scatter s(g, d);
      s.set_bucket_queue(!heap);
      s.reset(ins.starts, margin, seed, max_passes);
      std::vector<double> pass_ms;
      double t0 = cpu_ms(), last = t0;
      int seen = 0;
      work = 0;
      while (!s.step(Clock::time_point::max(), slice) && (work += s.work(), true))
        if (s.passes() != seen) {
          seen = s.passes();
          const double now = cpu_ms();
          pass_ms.push_back(now - last);
          last = now;
        }
      work += s.work();
      if (s.passes() != seen) pass_ms.push_back(cpu_ms() - last);
      if (best.empty()) best = pass_ms;
      for (size_t k = 0; k < best.size() && k < pass_ms.size(); ++k) best[k] = std::min(best[k], pass_ms[k]);
      collisions = s.collisions();
      passes = s.passes();
      hash = 1469598103934665603ull;
      for (int i = 0; i < agents; ++i)
        for (Vertex v : s.path(i)) hash = (hash ^ static_cast<uint64_t>(v + 1)) * 1099511628211ull;
    }
    nlohmann::json j;
    j["map"] = map_file;
    j["scen"] = scen_file;
    j["agents"] = agents;
    j["margin"] = margin;
    j["seed"] = seed;
    j["queue"] = heap ? "heap" : "bucket";
    j["passes"] = passes;
    j["pass_cpu_ms"] = best;
    double total = 0;
    for (double x : best) total += x;
    j["total_cpu_ms"] = total;
    j["collisions"] = collisions;
    j["work"] = work;
    j["paths_hash"] = std::to_string(hash);
    std::cout << j.dump() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "rtlacam-suo-bench: " << e.what() << std::endl;
    return cli::kBadInput;
  }
  return cli::kOk;
}
