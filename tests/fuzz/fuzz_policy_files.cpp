// libFuzzer target: the policy's binary readers, weights (policy::load_weights) and golden
// files (policy::load_golden), which share BinaryReader. Both read the same input.
#include "fuzz_util.hpp"
#include "planner/error.hpp"
#include "policy/golden_file.hpp"
#include "policy/weights_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const std::string path = fuzz::temp_path("fuzz.bin");
  fuzz::write_file(path, std::string(reinterpret_cast<const char*>(data), size));
  try {
    const policy::Model m = policy::load_weights(path);
    (void)m.num_parameters();
  } catch (const planner::InputError& e) {
    fuzz::expected(e);
  } catch (const std::exception& e) {
    fuzz::unexpected(e);
  }
  try {
    policy::load_golden(path);
  } catch (const planner::InputError& e) {
    fuzz::expected(e);
  } catch (const std::exception& e) {
    fuzz::unexpected(e);
  }
  return 0;
}
