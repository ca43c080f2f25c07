#pragma once
// SumoError: anything that went wrong inside SUMO or the connection to it, as one line
// ("SUMO <call>: <what SUMO said>"). libsumo throws std::exception subclasses that are not
// in its public headers (ProcessError, FatalTraCIError, ...), so the back ends catch
// std::exception at every call and rethrow this one type.
#include <stdexcept>
#include <string>

namespace controller {

struct SumoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A violation of the executed plan (an invalid MAPF step, AGVs overlapping, a SUMO
// collision, position drift beyond re-sync): the run stops with this message, counted
// in metrics.json:violations; rtlacam-sumo exits 3.
struct ControlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An AGV that vanished or moved on its own (removed behind the controller's back, arrived
// at a route end, teleported by SUMO): a runtime fault, not a plan violation -- the run
// stops with this message, no violation counted; rtlacam-sumo exits 1.
struct FleetError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace controller
