#include "controller/sumo_options.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <thread>

#include "controller/sumo_error.hpp"
#include "planner/output_file.hpp"

namespace controller {

static std::string num(double x)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string write_vtype_file(const Config& cfg, const std::string& dir, double max_spacing)
{
  const VType& t = cfg.fleet.vtype;
  // Commanded speeds are (distance / tick); the margin keeps rounding from capping them.
  // adg: the Driver's top speed (it never exceeds max_speed x speed factor).
  const double vmax = cfg.run.executor != "lockstep" ? 1.01 * t.max_speed : 1.01 * max_spacing / cfg.run.tick_s;
  const double emergency = std::max(2 * vmax / cfg.sumo.step_length, t.decel);
  const std::string path = dir + "/agv.add.xml";
  planner::write_file(path, [&](std::ostream& out) {
    out << "<additional>\n"
        << "    <vType id=\"agv\" length=\"" << num(t.length) << "\" width=\"" << num(t.width) << "\" minGap=\""
        << num(t.min_gap) << "\" accel=\"" << num(t.accel) << "\" decel=\"" << num(t.decel) << "\" emergencyDecel=\""
        << num(emergency) << "\" maxSpeed=\"" << num(vmax)
        << "\" speedFactor=\"1\" speedDev=\"0\" sigma=\"0\" guiShape=\"truck\"/>\n"
        << "</additional>\n";
  });
  return path;
}

std::string write_gui_settings(const Config& cfg, const std::string& dir)
{
  // Names scale with the zoom (constantSize 0; size 20 is about 1 m high in 1.15): a third
  // of a cell, so they stay on their AGV and never cover the net when zoomed out.
  const std::string size = num(7.0 * cfg.grid.cell_length);
  const std::string path = dir + "/gui.xml";
  planner::write_file(path, [&](std::ostream& out) {
    out << "<viewsettings>\n"
        << "    <scheme name=\"rtlacam\">\n"
        << "        <vehicles vehicleQuality=\"2\" vehicle_minSize=\"0\" vehicle_exaggeration=\"1\" "
           "vehicle_constantSize=\"0\" showBlinker=\"0\" vehicleName_show=\"1\" vehicleName_size=\""
        << size
        << "\" vehicleName_color=\"black\" vehicleName_bgColor=\"255,255,255,160\" vehicleName_constantSize=\"0\" "
           "vehicleName_onlySelected=\"0\"/>\n"

        << "        <polys poly_minSize=\"0\" poly_exaggeration=\"1\" poly_constantSize=\"0\" polyName_show=\"0\" "
           "polyType_show=\"1\" polyType_size=\""
        << size << "\" polyType_color=\"0,110,120\" polyType_constantSize=\"0\" polyType_onlySelected=\"0\"/>\n"
        << "    </scheme>\n";
    // sumo-gui's own snapshots of its view (output.gui_snapshots), absolute: sumo-gui may
    // run in another working directory (an external one over TraCI).
    for (double t : cfg.output.gui_snapshots)
      out << "    <snapshot file=\"" << std::filesystem::absolute(dir + "/gui_" + num(t) + ".png").string()
          << "\" time=\"" << num(t) << "\"/>\n";
    out << "</viewsettings>\n";
  });
  return path;
}

std::vector<SumoOutput> sumo_outputs(const Config& cfg, const std::string& dir)
{
  const SumoOutputs& o = cfg.sumo.outputs;
  std::vector<SumoOutput> v;
  if (o.fcd) v.push_back({dir + "/fcd.xml", "fcd-export"});
  if (o.tripinfo) v.push_back({dir + "/tripinfo.xml", "tripinfos"});
  if (o.summary) v.push_back({dir + "/summary.xml", "summary"});
  if (o.collision) v.push_back({dir + "/collision.xml", "collisions"});
  return v;
}

void check_sumo_outputs(const Config& cfg, const std::string& dir, double wait_s)
{
  const auto t0 = std::chrono::steady_clock::now();
  for (const SumoOutput& f : sumo_outputs(cfg, dir))
    for (;;) {
      try {
        planner::check_xml_output(f.path, f.root);
        break;
      } catch (const planner::OutputError&) {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >= wait_s) throw;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    }
}

std::vector<std::string> sumo_args(const Config& cfg, const std::string& dir, const std::string& vtype_file,
                                   bool ignore_route_errors)
{
  // The stations file too: sumo-gui (and an external SUMO) shows them; SUMO checks them.
  const std::string additional = cfg.sumo.additional.empty() ? vtype_file : vtype_file + "," + cfg.sumo.additional;
  std::vector<std::string> a{"-n",
                             cfg.sumo.net,
                             "-a",
                             additional,
                             "--step-length",
                             num(cfg.sumo.step_length),
                             "--time-to-teleport",
                             "-1",
                             "--collision.action",
                             "warn",
                             "--collision.mingap-factor",
                             "0",
                             "--no-step-log",
                             "true"};
  if (ignore_route_errors) a.push_back("--ignore-route-errors");
  for (const SumoOutput& f : sumo_outputs(cfg, dir)) {
    if (f.root == "fcd-export")
      a.insert(a.end(), {"--fcd-output", f.path, "--fcd-output.attributes", "x,y,angle,speed,lane,pos"});
    else if (f.root == "tripinfos")
      a.insert(a.end(), {"--tripinfo-output", f.path, "--tripinfo-output.write-unfinished", "true"});
    else if (f.root == "summary")
      a.insert(a.end(), {"--summary-output", f.path});
    else
      a.insert(a.end(), {"--collision-output", f.path});
  }
  if (cfg.run.gui)
    a.insert(a.end(), {"--start", "true", "--quit-on-end", "true", "--delay", num(cfg.run.gui_delay_ms),
                       "--window-size", "1280,800", "--window-pos", "0,0", "--gui-settings-file", dir + "/gui.xml"});
  a.insert(a.end(), cfg.sumo.extra_args.begin(), cfg.sumo.extra_args.end());
  return a;
}

}  // namespace controller
