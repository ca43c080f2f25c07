// libFuzzer target: the LoRR agents and tasks readers (tasks::load_lorr_agents,
// tasks::load_lorr_tasks) on a fixed 32x32 map. Both read the same input.
#include "fuzz_util.hpp"
#include "planner/error.hpp"
#include "planner/movingai.hpp"
#include "tasks/lorr_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const planner::Graph g = planner::load_map(RTLACAM_FUZZ_DATA "/planner/random-32-32-20.map");
  static const std::string path = fuzz::temp_path("fuzz.lorr");
  fuzz::write_file(path, std::string(reinterpret_cast<const char*>(data), size));
  auto run = [](auto f) {
    try {
      f();
    } catch (const planner::InputError& e) {
      fuzz::expected(e);
    } catch (const std::exception& e) {
      fuzz::unexpected(e);
    }
  };
  run([&] { tasks::load_lorr_agents(path, g); });
  run([&] { tasks::load_lorr_agents(path, g, 3); });
  run([&] { tasks::load_lorr_tasks(path, g); });
  return 0;
}
