#pragma once
// The SUMO side of a run: the AGV vType file and the command-line options of scheme S.
//   -n net -a agv.add.xml[,stations]            (stations: sumo.additional, shown in sumo-gui)
//   --step-length dt --time-to-teleport -1      (waiting AGVs are never teleported)
//   --collision.action warn --collision.mingap-factor 0   (report physical overlaps only,
//                                                          never remove or teleport)
//   --no-step-log true, outputs (fcd/tripinfo/summary/collision) into the run's dir,
//   then the user's extra_args (they come last, so they can override).
#include <string>
#include <vector>

#include "controller/config.hpp"

namespace controller {

// Writes <dir>/agv.add.xml with vType "agv": the config's body sizes, speedFactor 1,
// speedDev 0, sigma 0, maxSpeed a little above max_spacing / tick and emergencyDecel >=
// maxSpeed / step_length (a stop from full speed within one step raises no warning).
// Returns the file's path.
std::string write_vtype_file(const Config& cfg, const std::string& dir, double max_spacing);

// run.gui: writes <dir>/gui.xml, sumo-gui's view settings (--gui-settings-file): vehicles
// at their vType's size (no exaggeration, no minimum size) with their ids, the goal
// markers (fleet_view.hpp) with theirs; a snapshot of the view at each of output.gui_snapshots.
// Returns the file's path.
std::string write_gui_settings(const Config& cfg, const std::string& dir);

// SUMO's output files of the config (sumo.outputs) in `dir`: path and XML root element
// (SUMO writes the root's closing tag only at its close, so a complete file ends with it).
struct SumoOutput {
  std::string path, root;
};
std::vector<SumoOutput> sumo_outputs(const Config& cfg, const std::string& dir);

// After SUMO closed: every output complete (planner::check_xml_output). Throws
// planner::OutputError naming the first file that is not. A SUMO behind TraCI (a child or
// an external one) writes its outputs after it acknowledged the close, in its own process:
// an incomplete file is looked at again for up to `wait_s` seconds.
void check_sumo_outputs(const Config& cfg, const std::string& dir, double wait_s = 0);

std::vector<std::string> sumo_args(const Config& cfg, const std::string& dir, const std::string& vtype_file,
                                   bool ignore_route_errors);

}  // namespace controller
