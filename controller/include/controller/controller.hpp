#pragma once
// Controller: one SUMO run in which a real-time planner drives every AGV cell by cell.
//
//   gridify(net) -> CellMap; fleet -> starts/goals; start SUMO; insert the AGVs
//   every SUMO step:  planner.search(budget)            (thinking while the AGVs move)
//   run.executor: lockstep -- every tick (tick_s / step_length steps), at its start:
//       next = planner.next(); planner.commit()         (reroot at once: the search goes on
//                                                        from where the AGVs are heading)
//       validator.step(next); commander.command(cur, next)   (scheme S)
//     at its end: commander.verify(next)                (exact poses, else moveTo + count)
//   run.executor: adg -- the planner commits up to run.window configurations ahead into an
//     action dependency graph; the Driver starts each AGV's moves when released and
//     drives it with accel / decel (driver.hpp)
//   rotation solvers (pibt-rot, epibt, wppl; lockstep): the committed step's actions also
//     turn AGVs on their cells, fleet.turn_s per quarter turn, SUMO's angle animated
//     (Commander::orient); check_rotation_step checks every step's actions
//   after every SUMO step: no AGV arrived, teleported or collided, and Safety: no overlap,
//   every AGV on its committed path (safety.hpp).
// Any violation stops the run with a one-line error in Metrics::error; the outputs
// (SUMO files, metrics.json, plan.txt) are written in every case.
#include <functional>
#include <memory>

#include "controller/config.hpp"
#include "controller/executed_plan.hpp"
#include "controller/metrics.hpp"
#include "controller/sumo_backend.hpp"
#include "gridify/cell_map.hpp"
#include "planner/action_preference.hpp"
#include "planner/realtime_planner.hpp"
#include "planner/zones.hpp"

namespace controller {

class Run;

// The solver named by planner.solver on this graph and instance; `pref` orders PIBT's
// moves (a learned policy), `test` replaces "all at goals" (lifelong runs). Rotation
// solvers take planner.rotation and each AGV's start heading (`headings`; empty: east).
// Cell solvers keep their distance tables in `cache` when given (shared with the planner a
// stuck replan replaces: stuck_replan.hpp).
std::unique_ptr<planner::RealtimePlanner> make_planner(const PlannerSection& p, const planner::Graph& g,
                                                       const planner::Config& starts, const planner::Config& goals,
                                                       planner::ActionPreference* pref = nullptr,
                                                       planner::GoalTest test = {},
                                                       const std::vector<int>& headings = {},
                                                       std::shared_ptr<planner::DistCache> cache = nullptr,
                                                       std::shared_ptr<const planner::Zones> zones = nullptr);

// The back end named by run.backend (run.gui: sumo-gui through TraCI).
std::unique_ptr<SumoBackend> make_backend(const RunSection& r);

class Controller {
 public:
  explicit Controller(Config cfg) : cfg_(std::move(cfg)) {}

  // Runs to the goals or run.max_ticks. Bad configuration (including cells off the
  // graph) throws ConfigError before SUMO starts; everything later ends up in
  // Metrics::error.
  Metrics run();

  // Called at the start of every tick, before the commands: lets tests (or tools) act on
  // SUMO from outside, e.g. remove an AGV behind the controller's back.
  std::function<void(long long tick, SumoBackend& sumo)> on_tick;
  // Called before every SUMO step, after the controller's commands, with the poses read
  // after the previous step (empty before the first): a second client acting on the AGVs
  // in the same step -- tests inject outside stops with it.
  std::function<void(SumoBackend& sumo, const std::vector<VehiclePose>& poses)> on_step;
  // Called before every SUMO step of the final stop (every AGV braked to rest before the
  // controller detaches): tests act on SUMO from outside there too.
  std::function<void(SumoBackend& sumo)> on_stop_step;
  // Metres an AGV may be off its cell after a tick before it is re-synced.
  double tolerance = 1e-6;

  const gridify::CellMap& map() const { return map_; }
  // The executed plan; in a lifelong run only its recent part (executed_plan.hpp: the rest
  // is in plan.txt) once it outgrows output.plan_keep configurations.
  const std::vector<planner::Config>& plan() const { return plan_.kept(); }

 private:
  friend class Run;  // the phases of run() (src/run.hpp)
  Config cfg_;
  gridify::CellMap map_;
  ExecutedPlan plan_;
};

}  // namespace controller
