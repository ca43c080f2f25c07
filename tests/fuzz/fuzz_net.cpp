// libFuzzer target: the SUMO .net.xml reader (gridify::NetFile::read) and gridify() on
// the parsed net, with default options and with snap + drop_one_way. The input is the
// net, optionally followed by a NUL byte and an additional file with stations.
//
// rtlacam-gridify catches only planner::InputError, so any other exception escaping
// gridify() would terminate it: here it is always a finding (not only in strict mode).
#include "fuzz_util.hpp"
#include "gridify/gridifier.hpp"
#include "gridify/movingai_map.hpp"
#include "gridify/net_file.hpp"
#include "planner/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const std::string net_path = fuzz::temp_path("fuzz.net.xml");
  static const std::string add_path = fuzz::temp_path("fuzz.add.xml");
  const auto parts = fuzz::split(data, size, 2);
  fuzz::write_file(net_path, parts[0]);
  if (parts.size() > 1) fuzz::write_file(add_path, parts[1]);
  gridify::NetFile net;
  try {
    net = gridify::NetFile::read(net_path);
  } catch (const planner::InputError& e) {
    fuzz::expected(e);
    return 0;
  } catch (const std::exception& e) {
    fuzz::finding("exception other than InputError", e);
  }
  for (bool lenient : {false, true}) {
    gridify::GridifyOptions opt;
    opt.snap = opt.drop_one_way = lenient;
    if (parts.size() > 1) opt.additional = add_path;
    try {
      const gridify::CellMap m = gridify::gridify(net, opt);
      std::string why;
      (void)gridify::grid_layout(m, &why);
    } catch (const planner::InputError& e) {
      fuzz::expected(e);
    } catch (const std::exception& e) {
      fuzz::finding("exception other than InputError", e);
    }
  }
  return 0;
}
