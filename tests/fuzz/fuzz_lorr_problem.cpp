// libFuzzer target: the LoRR problem JSON (tasks::load_lorr_problem). The input is the
// problem file, optionally followed by a NUL byte and the simulation_time.json beside it.
#include "fuzz_util.hpp"
#include "planner/error.hpp"
#include "tasks/lorr_problem.hpp"

#include <filesystem>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const std::string dir = [] {
    const std::string d = fuzz::temp_path("lorr");
    std::filesystem::create_directories(d);
    return d + "/";
  }();
  const auto parts = fuzz::split(data, size, 2);
  const std::string problem = fuzz::write_file(dir + "RANDOM-01.json", parts[0]);
  if (parts.size() > 1) fuzz::write_file(dir + "simulation_time.json", parts[1]);
  else std::remove((dir + "simulation_time.json").c_str());
  try {
    const tasks::LorrProblem p = tasks::load_lorr_problem(problem);
    // An accepted problem has a pool of at least one task per agent.
    if (p.pool_size() < p.team_size) {
      std::fprintf(stderr, "\nFUZZ FINDING: pool_size %d < teamSize %d\n", p.pool_size(), p.team_size);
      std::abort();
    }
    (void)p.default_mode();
  } catch (const planner::InputError& e) {
    fuzz::expected(e);
  } catch (const std::exception& e) {
    fuzz::unexpected(e);
  }
  return 0;
}
