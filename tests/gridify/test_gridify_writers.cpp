// The outputs: JSON dump, SVG picture and MovingAI map of a gridification.
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gridify/gridifier.hpp"
#include "gridify/json_writer.hpp"
#include "gridify/movingai_map.hpp"
#include "gridify/svg_writer.hpp"
#include "gridify_test_util.hpp"
#include "planner/error.hpp"

using namespace gridify;
using namespace gridify_test;

namespace {

size_t count(const std::string& s, const std::string& part)
{
  size_t n = 0;
  for (size_t p = s.find(part); p != std::string::npos; p = s.find(part, p + 1)) ++n;
  return n;
}

CellMap small_map()
{
  GridifyOptions opt;
  opt.additional = scenario("small.add.xml");
  return gridify::gridify(scenario("small.net.xml"), opt);
}

}  // namespace

TEST(GridifyWriters, JsonHasCellsPosesAndEdges)
{
  CellMap m = small_map();
  std::string path = temp_dir() + "/small.json";
  write_json(m, path);
  std::ifstream in(path);
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["cells"].size(), m.cells.size());
  EXPECT_EQ(j["edges"].size(), m.graph.num_edges());
  EXPECT_EQ(j["aisles"].size(), m.aisles.size());
  EXPECT_EQ(j["stations"].size(), 5u);
  EXPECT_EQ(j["summary"]["cells"], 62);
  EXPECT_EQ(j["grid"]["width"], 13);
  for (const auto& c : j["cells"]) {
    EXPECT_TRUE(c["kind"] == "junction" || c["kind"] == "aisle");
    EXPECT_GE(c["poses"].size(), 1u);
    EXPECT_TRUE(c.contains("col"));
  }
  for (const auto& e : j["edges"]) EXPECT_TRUE(m.graph.adjacent(e[0], e[1]));
}

TEST(GridifyWriters, SvgDrawsEveryCellEdgeAndStation)
{
  CellMap m = small_map();
  std::string svg = to_svg(m);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(count(svg, "<rect x="), static_cast<size_t>(m.num_junction_cells()));
  // aisle cells + stations + legend dots
  EXPECT_EQ(count(svg, "<circle"), static_cast<size_t>(m.num_aisle_cells()) + m.stations.size() + 3);
  // aisle bands + graph edges
  EXPECT_EQ(count(svg, "<line"), m.aisles.size() + m.graph.num_edges());
  EXPECT_NE(svg.find(">pickup1<"), std::string::npos);
  std::string path = temp_dir() + "/small.svg";
  write_svg(m, path);
  std::ifstream in(path);
  EXPECT_TRUE(in.good());
}

TEST(GridifyWriters, SvgShowsDroppedParts)
{
  CellMap m = gridify::gridify(data("disconnected.net.xml"));
  std::string svg = to_svg(m);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find("component e, f"), std::string::npos);
}

TEST(GridifyWriters, MovingAiMapOfTheSmallWarehouse)
{
  CellMap m = small_map();
  std::string path = temp_dir() + "/small.map";
  write_movingai_map(m, path);
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string s = ss.str();
  EXPECT_EQ(s.rfind("type octile\nheight 13\nwidth 13\nmap\n", 0), 0u);
  EXPECT_EQ(count(s, "."), m.cells.size());
  // Top row: the two drop stations at x = 0 and x = 12.
  EXPECT_NE(s.find("\n.@@@@@@@@@@@.\n"), std::string::npos);
}

TEST(GridifyWriters, MovingAiMapRefusesSnappedNets)
{
  GridifyOptions opt;
  opt.snap = true;
  CellMap m = gridify::gridify(data("notmultiple.net.xml"), opt);
  try {
    write_movingai_map(m, temp_dir() + "/x.map");
    FAIL() << "expected an error";
  } catch (const planner::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("snapped"), std::string::npos) << e.what();
  }
}
