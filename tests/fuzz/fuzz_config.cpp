// libFuzzer target: the controller's YAML config (controller::parse_config), without SUMO.
// Relative paths resolve against sumo_scenarios/, so "net: small.net.xml" is found.
#include "controller/config.hpp"
#include "fuzz_util.hpp"

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string yaml(reinterpret_cast<const char*>(data), size);
  try {
    const controller::Config c = controller::parse_config(yaml, "fuzz.yaml", RTLACAM_FUZZ_SCENARIOS);
    // An accepted config must mean what it says: a tick is a whole number of SUMO steps.
    const int steps = c.steps_per_tick();
    if (steps < 1 || std::fabs(steps * c.sumo.step_length - c.run.tick_s) > 1e-6 * c.run.tick_s) {
      std::fprintf(stderr, "\nFUZZ FINDING: accepted tick_s %g / step_length %g gives %d steps per tick\n",
                   c.run.tick_s, c.sumo.step_length, steps);
      std::abort();
    }
  } catch (const controller::ConfigError& e) {
    fuzz::expected(e);
  } catch (const std::exception& e) {
    fuzz::unexpected(e);
  }
  return 0;
}
