#pragma once
// FleetView: what a person sees of the fleet in SUMO (sumo-gui, or any TraCI client that
// reads colours and polygons). The one place that maps an AGV's state to its colour (the
// legend in controller/README.md), and one goal marker per AGV: a square outline polygon
// "goal_<agv id>" (type: the AGV's id) centred on the goal cell's x/y. Only changes cost a SUMO call: with 1000 AGVs a step where nothing
// changed state sends nothing.
#include <cstdint>
#include <string>
#include <vector>

#include "controller/sumo_backend.hpp"
#include "gridify/cell_map.hpp"
#include "planner/config.hpp"

namespace controller {

// Highest precedence last: an AGV that is several of these shows the last that applies.
enum class AgvState : uint8_t {
  Idle,      // at rest with no move of its own to make (on its goal, or the plan has it wait)
  Moving,    // driving a committed move (or starting it this tick)
  Carrying,  // Moving with a load: lifelong, its task's first errand (pick-up) done
  Waiting,   // stands with a committed move the executor holds back (a dependency: adg; the
             // whole fleet waits for a stopped AGV: lockstep)
  Delayed,   // stopped by the delay model (random stops, scripted delays.stuck)
  Stuck,     // made immobile by the stuck-AGV replan (run.replan_on_stuck)
};
constexpr int kAgvStates = 6;

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
};

// Precedence of the flags: stuck > delayed > waiting > moving (carrying if loaded) > idle.
AgvState agv_state(bool stuck, bool delayed, bool waiting, bool moving, bool carrying);
Rgb state_colour(AgvState s);
const char* state_name(AgvState s);
// Colour of the goal markers (one for all: the marker's type names the AGV).
Rgb goal_colour();

struct ViewStats {
  long long colour_calls = 0;  // Vehicle.setColor sent
  long long goal_calls = 0;    // Polygon.add / Polygon.setShape sent
  double ms = 0;               // wall time: the states, show() and goals() (Run measures it)
};

class FleetView {
 public:
  // `ids`: SUMO vehicle ids in agent order; `marker_m`: goal marker side (m).
  FleetView(SumoBackend& sumo, const gridify::CellMap& map, std::vector<std::string> ids, double marker_m);

  static std::string goal_id(const std::string& vehicle) { return "goal_" + vehicle; }

  // Colours every AGV by its state; a call only where the state changed since the last show().
  void show(const std::vector<AgvState>& states);
  // Moves each AGV's goal marker to its goal cell (the first call adds them).
  void goals(const planner::Config& goals);
  const ViewStats& stats() const { return st_; }
  void add_ms(double ms) { st_.ms += ms; }

 private:
  SumoBackend& sumo_;
  const gridify::CellMap& map_;
  std::vector<std::string> ids_;
  double marker_;
  std::vector<int> shown_;         // state last sent per agent, -1 = none yet
  planner::Config goal_;           // goal cell last marked per agent, empty = none yet
  ViewStats st_;
};

}  // namespace controller
