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

// A violation of the executed plan (position drift beyond re-sync, an AGV that vanished,
// a SUMO collision/teleport/arrival, an invalid MAPF step): the run stops with this message.
struct ControlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace controller
