// rtlacam-ggo: offline guidance graph optimisation (GGO, Zhang et al. IJCAI 2024) for the
// rotation model: CMA-ES over LaneGuidance's per-lane log-multipliers of the arrow field,
// fitness = errands/step of epibt on LoRR problems (in-process, deterministic), relative to
// the arrow field's on the same (problem, seed). Writes the best guidance so far after
// every generation (--out, loadable with rtlacam-lifelong --guidance FILE), its parameters
// (--out.params, reusable with --init), the CMA-ES mean (--out.mean.params) and a log of
// every evaluation (--log).
#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "../../apps/cli.hpp"
#include "ggo/cmaes.hpp"
#include "ggo/fitness.hpp"
#include "ggo/lane_guidance.hpp"
#include "planner/error.hpp"
#include "planner/output_file.hpp"

namespace {

Eigen::VectorXd load_params(const std::string& path, int n)
{
  std::ifstream in(path);
  if (!in) throw planner::input_error(path, 0, "cannot open parameter file");
  Eigen::VectorXd p(n);
  int k = 0;
  std::string line;
  for (int no = 1; std::getline(in, line); ++no) {
    if (line.empty() || line[0] == '#') continue;
    if (k == n) throw planner::input_error(path, no, "more than " + std::to_string(n) + " parameters");
    size_t end = 0;
    try {
      p[k] = std::stod(line, &end);
    } catch (const std::exception&) {
      end = 0;
    }
    if (end == 0) throw planner::input_error(path, no, "'" + line + "' is not a number");
    ++k;
  }
  if (k != n) throw planner::input_error(path, 0, std::to_string(k) + " parameters, expected " + std::to_string(n));
  return p;
}

void save_params(const std::string& path, const Eigen::VectorXd& p, const std::string& header)
{
  planner::write_file(path, [&](std::ostream& out) {
    out << "# " << header << "\n";
    for (int i = 0; i < p.size(); ++i) out << p[i] << '\n';
  });
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Offline guidance graph optimisation (CMA-ES, epibt throughput) for the rotation model"};
  std::vector<std::string> problems;
  std::vector<uint64_t> seeds{0};
  long steps = 500, final_steps = 0;
  int generations = 1000, lambda = 0, unit = 4, lns = 20;
  double minutes = 60, sigma = 0.2;
  uint64_t cma_seed = 0;
  std::string out_file, log_file, init_file;
  app.add_option("--problem", problems, "LoRR problem JSON (repeatable: fitness is the mean over problems and seeds)")->required();
  app.add_option("--seeds", seeds, "planner seeds of each evaluation")->capture_default_str();
  app.add_option("--steps", steps, "steps of an evaluation run (<= 0: the problem's)")->capture_default_str();
  app.add_option("--generations", generations, "CMA-ES generations at most")->capture_default_str();
  app.add_option("--max-minutes", minutes, "stop after the generation that passes this wall time")->capture_default_str();
  app.add_option("--sigma", sigma, "initial step size (log-multiplier)")->capture_default_str();
  app.add_option("--lambda", lambda, "candidates per generation (0: 4 + 3 ln n)")->capture_default_str();
  app.add_option("--cma-seed", cma_seed, "CMA-ES sampling seed")->capture_default_str();
  app.add_option("--unit", unit, "cost of an arrow-field 'along' move (costs are integers)")->capture_default_str();
  app.add_option("--epibt-lns", lns, "epibt LNS rounds (fixed: deterministic fitness)")->capture_default_str();
  app.add_option("--init", init_file, "start mean: a parameter file written by a previous run (default: the arrow field)");
  app.add_option("--final-steps", final_steps, "after the search: best vs arrows with this many steps (<= 0: the problem's), reported in the file header")
      ->capture_default_str();
  app.add_option("--out", out_file, "best guidance file (+ .params)")->required();
  app.add_option("--log", log_file, "evaluation log (TSV)")->required();
  cli::add_version(app, "rtlacam-ggo");
  RTLACAM_PARSE(app, argc, argv);

  std::ostringstream cmd;
  for (int i = 0; i < argc; ++i) cmd << (i ? " " : "") << argv[i];
  try {
    std::vector<ggo::Problem> prs;
    for (const std::string& p : problems) {
      prs.push_back(ggo::load_problem(p));
      if (steps <= 0 && prs.back().steps <= 0) throw planner::input_error(p, 0, "no simulation time: pass --steps");
    }
    const planner::Graph& g = prs[0].g;
    for (const ggo::Problem& p : prs)
      if (p.g.size() != g.size()) throw planner::InputError(p.name + ": every --problem must be on the same map");
    const ggo::LaneGuidance lanes(g, unit);
    planner::Epibt::Options ep;
    ep.lns_rounds = lns;
    // The READMEs' out/ggo/... paths: make their folders (as rtlacam-sumo makes output.dir).
    for (const std::string& f : {log_file, out_file}) {
      const std::filesystem::path parent = std::filesystem::path(f).parent_path();
      std::error_code ec;
      if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    }
    std::ofstream log(log_file);
    if (!log) throw planner::OutputError("cannot write '" + log_file + "': " + std::strerror(errno));
    log << "# " << cmd.str() << "\ngen\tcand\tfitness\tthroughputs\tsigma\tsecs\n";
    const auto t0 = std::chrono::steady_clock::now();
    auto secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    // Baseline: the arrow field as rtlacam-lifelong --guidance arrows builds it.
    const planner::Guidance arrows = planner::arrow_guidance(g, 1, 3, 1);
    std::vector<double> base;
    for (const ggo::Problem& p : prs)
      for (uint64_t s : seeds) base.push_back(ggo::evaluate(p, arrows, steps, s, ep).throughput);
    long evals = 0;
    // Fitness: mean ratio to the arrow field (every problem weighs the same); planner errors: 0.
    auto fitness = [&](const planner::Guidance& gd, std::string& detail) {
      double sum = 0;
      size_t k = 0;
      std::ostringstream d;
      for (const ggo::Problem& p : prs)
        for (uint64_t s : seeds) {
          const ggo::Evaluation e = ggo::evaluate(p, gd, steps, s, ep);
          d << (k ? "," : "") << e.throughput;
          if (e.planner_errors > 0) d << "(errors " << e.planner_errors << ")";
          sum += e.planner_errors > 0 ? 0 : e.throughput / base[k];
          ++k;
        }
      ++evals;
      detail = d.str();
      return sum / static_cast<double>(k);
    };
    Eigen::VectorXd mean = init_file.empty() ? Eigen::VectorXd::Zero(lanes.dims()) : load_params(init_file, lanes.dims());
    std::string detail;
    double best_f = fitness(lanes.to_guidance(g, mean), detail);
    Eigen::VectorXd best = mean;
    log << "0\tstart\t" << best_f << '\t' << detail << '\t' << sigma << '\t' << secs() << std::endl;
    std::cerr << "start (" << (init_file.empty() ? "arrows x" + std::to_string(unit) : init_file) << "): " << best_f << " of arrows\n";
    auto write_best = [&](const std::string& note) {
      std::ostringstream h;
      h << "rtlacam-ggo (tools/ggo): CMA-ES over per-lane multipliers of the arrow field 1,3,1 (unit " << unit << ")\n"
        << "command: " << cmd.str() << "\n"
        << "evaluations: " << evals << ", fitness (errands/step / arrows', mean over problems x seeds, " << steps
        << " steps): " << best_f << "\n"
        << note;
      planner::save_guidance(g, lanes.to_guidance(g, best), out_file, h.str());
      save_params(out_file + ".params", best, "rtlacam-ggo parameters (LaneGuidance), fitness " + std::to_string(best_f));
    };
    write_best("");
    ggo::CmaesOptions co;
    co.lambda = lambda;
    co.seed = cma_seed;
    ggo::Cmaes es(mean, sigma, co);
    for (int gen = 1; gen <= generations && secs() < minutes * 60; ++gen) {
      const std::vector<Eigen::VectorXd>& xs = es.ask();
      std::vector<double> f(xs.size());
      for (size_t k = 0; k < xs.size(); ++k) {
        const double fit = fitness(lanes.to_guidance(g, xs[k]), detail);
        f[k] = -fit;  // CMA-ES minimises
        log << gen << '\t' << k << '\t' << fit << '\t' << detail << '\t' << es.sigma() << '\t' << secs() << std::endl;
        if (fit > best_f) best_f = fit, best = xs[k];
      }
      es.tell(f);
      write_best("");
      // The distribution's mean: less overfitted to the fitness runs' noise than the best sample.
      save_params(out_file + ".mean.params", es.mean(), "rtlacam-ggo CMA-ES mean after generation " + std::to_string(gen));
      std::cerr << "gen " << gen << ": best " << best_f << " gen best " << -*std::min_element(f.begin(), f.end())
                << " sigma " << es.sigma() << " evals " << evals << " " << static_cast<int>(secs()) << " s" << std::endl;
      log << "# gen " << gen << " best " << best_f << " sigma " << es.sigma() << std::endl;
    }
    if (final_steps >= 0 && app.count("--final-steps")) {
      std::ostringstream note;
      const planner::Guidance gd = lanes.to_guidance(g, best);
      for (const ggo::Problem& p : prs)
        for (uint64_t s : seeds) {
          const ggo::Evaluation a = ggo::evaluate(p, arrows, final_steps, s, ep);
          const ggo::Evaluation b = ggo::evaluate(p, gd, final_steps, s, ep);
          note << "full run " << p.name << " seed " << s << " (" << (final_steps > 0 ? final_steps : p.steps)
               << " steps): arrows " << a.throughput << ", this " << b.throughput << " (x" << b.throughput / a.throughput
               << "), planner errors " << b.planner_errors << "\n";
        }
      std::cerr << note.str();
      log << "# final\n# " << note.str();
      write_best(note.str());
    }
    log.flush();  // the log is written as it goes; a full disk shows here at the latest
    if (!log) throw planner::OutputError("cannot write '" + log_file + "'");
  } catch (const planner::InputError& e) {
    std::cerr << "rtlacam-ggo: " << e.what() << std::endl;
    return cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "rtlacam-ggo: " << e.what() << std::endl;
    return cli::kRuntimeError;
  }
  return cli::kOk;
}
