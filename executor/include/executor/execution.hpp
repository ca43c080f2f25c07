#pragma once
// Execution: the seam between a real-time planner's committed configurations and the robots
// (the LoRR Start-Kit's Executor, in three methods). The planner side pushes configurations
// while can_accept(); every tick step() moves the robots; positions() is where they are.
//
//   GraphExecution    (graph_execution.hpp)    cell plans on the MAPF graph under a delay
//                                              model: lockstep | adg | adg-follow
//   RotationExecution (rotation_execution.hpp) cell plans run by robots with a heading
//                                              (LoRR MAPF_T): turns cost steps, cells are
//                                              entered in plan order
// A planner that plans robot actions itself (the rotation solvers) needs no Execution: its
// configuration is the robots'.
//
// What every implementation guarantees: positions() after each step() is an executed
// configuration that the Validator accepts as a step from the one before (no vertex or
// swap conflict, moves along edges), and every pushed configuration is eventually reached
// under finite delays.
#include <string>
#include <vector>

#include "planner/config.hpp"

namespace executor {

class Execution {
 public:
  virtual ~Execution() = default;

  // Room for one more committed configuration (the window ahead of the slowest robot).
  virtual bool can_accept() const = 0;
  // The planner's next committed configuration: a valid step from the last one pushed.
  virtual void push(const planner::Config& next) = 0;
  // One tick of execution.
  virtual void step() = 0;
  // The executed configuration after the last step().
  virtual const planner::Config& positions() const = 0;
  // Everything pushed has been executed.
  virtual bool idle() const = 0;
  // With headings (RotationExecution): per robot, 0 east .. 3 north (planner/heading.hpp),
  // and the last step's LoRR letters (F, R, C, W). Empty for cell execution.
  virtual const std::vector<int>& headings() const { return kNone; }
  virtual const std::string& actions() const { return kNoActions; }

 private:
  static inline const std::vector<int> kNone{};
  static inline const std::string kNoActions{};
};

}  // namespace executor
