#pragma once
// RotationPlanner: a real-time planner that plans LoRR rotation actions (MAPF_T) itself,
// one F / R / C / W per robot per step, on RotationDist's (cell, heading) tables:
// RotationPibt (`pibt-rot`) and Wppl (`wppl`). The lifelong runner executes its actions
// directly (no cell plan, no RotationExecution), checks them (tasks::check_rotation_step),
// and prefetches the goals to come into its tables through this interface.
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "planner/rotation/guidance.hpp"
#include "planner/realtime_planner.hpp"
#include "planner/rotation/rotation_dist.hpp"

namespace planner {

class RotationPlanner : public RealtimePlanner {
 public:
  RotationPlanner* rotation() override { return this; }
  virtual const std::vector<int>& headings() const = 0;  // per robot, 0 east .. 3 north
  virtual const std::string& actions() const = 0;        // the planned step, one of "FRCW" per robot (after search())
  virtual uint16_t h(int agent) const = 0;               // steps from its state to its goal
  virtual const RotationDist& dist() const = 0;
  const Graph* graph() const override { return &dist().graph(); }
  // Lifelong runs: goals known to come (RotationDist::prefetch), grown in spare time.
  virtual void prefetch(const std::vector<Vertex>& goals) = 0;
  virtual bool precompute(std::chrono::steady_clock::time_point deadline) = 0;
  virtual size_t pending() const = 0;
  virtual void set_back_last(bool on) = 0;  // RotationPibt::set_back_last
  // The pocket exit rule (pocket_exit.hpp): pibt-rot and wppl (its rollouts); epibt has it
  // in EpibtOptions::pocket_exit.
  virtual void set_pocket_exit(bool on) { (void)on; }
  // Every robot's heading (0 east .. 3 north), one per robot, before the first step: robots
  // that do not all face one way at the start (SUMO AGVs face along their start lanes).
  virtual void set_headings(const std::vector<int>& headings) = 0;
  // Guidance (guidance.hpp): rank by action costs + guided distances. Drops the distance
  // tables and takes the goals' anew (call before the first step).
  virtual void set_guidance(Guidance gd) = 0;
  // Distance queries past `d` answer lower bounds (RotationDist::set_deadline).
  virtual void set_deadline(RotationDist::Deadline d) = 0;
};

}  // namespace planner
