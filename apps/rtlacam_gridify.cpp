// rtlacam-gridify: SUMO warehouse net (.net.xml) -> MAPF graph of cells.
// Prints a summary; optionally writes an SVG picture, a MovingAI .map and a JSON dump.
#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>

#include "cli.hpp"
#include "gridify/gridifier.hpp"
#include "gridify/json_writer.hpp"
#include "gridify/movingai_map.hpp"
#include "gridify/svg_writer.hpp"
#include "planner/error.hpp"

using namespace gridify;

int main(int argc, char** argv)
{
  CLI::App app{"Gridify a SUMO warehouse lane network into a MAPF graph of cells"};
  std::string net, svg, map, json;
  GridifyOptions opt;
  bool quiet = false;
  app.add_option("net", net, "SUMO network (.net.xml), built with netconvert --no-internal-links")->required();
  app.add_option("--cell-length", opt.cell_length, "metres between cells along an aisle")->capture_default_str();
  app.add_option("--tolerance", opt.tolerance, "metres of slack when checking lengths")->capture_default_str();
  app.add_flag("--snap", opt.snap, "stretch aisles whose length is not a multiple of the cell length");
  app.add_flag("--drop-one-way", opt.drop_one_way, "drop edges without an opposite edge (default: keep them as one-way arcs)");
  app.add_option("--additional", opt.additional, "SUMO additional file with stations (parkingArea, busStop, poi, ...)");
  app.add_option("--svg", svg, "write a picture of the gridification");
  app.add_option("--map", map, "write a MovingAI .map (axis-aligned grid nets only)");
  app.add_option("--json", json, "write cells, SUMO poses and edges as JSON");
  app.add_flag("--quiet,-q", quiet, "print nothing but errors");
  cli::add_version(app, "rtlacam-gridify");
  RTLACAM_PARSE(app, argc, argv);

  try {
    auto t0 = std::chrono::steady_clock::now();
    CellMap m = gridify::gridify(net, opt);
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!svg.empty()) write_svg(m, svg);
    if (!map.empty()) write_movingai_map(m, map);
    if (!json.empty()) write_json(m, json);
    if (quiet) return 0;

    std::cout << net << ": " << m.num_junction_cells() << " junctions, " << m.aisles.size() << " aisles, "
              << m.cells.size() << " cells (" << m.num_aisle_cells() << " in aisles), " << m.graph.num_edges()
              << " edges (" << m.graph.num_one_way() << " one-way), max degree " << m.graph.max_degree() << ", "
              << m.stations.size() << " stations, "
              << m.dropped.size() << " dropped; gridified in " << ms << " ms\n";
    for (const Dropped& d : m.dropped) std::cout << "  dropped " << d.kind << " " << d.id << ": " << d.reason << '\n';
    for (const std::string& w : m.warnings) std::cout << "  warning: " << w << '\n';
    for (const Station& s : m.stations) std::cout << "  station " << s.id << " (" << s.kind << ") at cell " << s.cell << '\n';
    std::string why;
    GridLayout g = grid_layout(m, &why);
    if (g.width > 0)
      std::cout << "  axis-aligned grid " << g.width << "x" << g.height
                << (m.graph.directed() ? " (no MovingAI export: one-way aisles)\n" : " (MovingAI export possible)\n");
    else std::cout << "  not a MovingAI grid: " << why << '\n';
  } catch (const planner::InputError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return cli::kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return cli::kRuntimeError;
  }
  return 0;
}
