// libFuzzer target: the MovingAI .scen reader (planner::load_scen) on a fixed 32x32 map.
#include "fuzz_util.hpp"
#include "planner/error.hpp"
#include "planner/movingai.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const planner::Graph g = planner::load_map(RTLACAM_FUZZ_DATA "/planner/random-32-32-20.map");
  static const std::string path = fuzz::temp_path("fuzz.scen");
  fuzz::write_file(path, std::string(reinterpret_cast<const char*>(data), size));
  // All agents, and a fixed count (the "asked for N agents" path).
  for (int num_agents : {-1, 5}) {
    try {
      planner::load_scen(path, g, num_agents);
    } catch (const planner::InputError& e) {
      fuzz::expected(e);
    } catch (const std::exception& e) {
      fuzz::unexpected(e);
    }
  }
  return 0;
}
