// libFuzzer target: the MovingAI .map reader (planner::load_map).
#include "fuzz_util.hpp"
#include "planner/error.hpp"
#include "planner/movingai.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const std::string path = fuzz::temp_path("fuzz.map");
  fuzz::write_file(path, std::string(reinterpret_cast<const char*>(data), size));
  try {
    planner::Graph g = planner::load_map(path);
    g.components();
  } catch (const planner::InputError& e) {
    fuzz::expected(e);
  } catch (const std::exception& e) {
    fuzz::unexpected(e);
  }
  return 0;
}
