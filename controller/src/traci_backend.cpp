// TraciBackend: SUMO over a TraCI socket (libtraci). Either starts `sumo`/`sumo-gui` as a
// child (libtraci popen()s the command joined by spaces, unquoted: paths with spaces
// break, so they are refused here) or connects to a SUMO already listening on a port and
// reloads it (TraCI load) with the run's options: the net, the `agv` vType and stations,
// the step length and the configured outputs -- an external SUMO started with only
// `--remote-port P` (or anything else) then runs exactly the configured simulation.
// Every call is a round trip (~12-40 us), so the controller reads poses once per tick.
#include <libsumo/libtraci.h>

#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>

#include "controller/sumo_backend.hpp"
#include "controller/sumo_error.hpp"

namespace controller {
namespace {

namespace api = libtraci;
constexpr bool kOverSocket = true;
#include "backend_impl.ipp"

// An external SUMO resolves file names against its own working directory: pass absolute
// ones (comma-separated lists too).
std::vector<std::string> absolute_files(std::vector<std::string> args)
{
  static const std::set<std::string> kFileOptions{"-n", "--net-file", "-a", "--additional-files", "-r",
                                                  "--route-files", "--fcd-output", "--tripinfo-output",
                                                  "--summary-output", "--collision-output", "--gui-settings-file"};
  for (size_t i = 0; i + 1 < args.size(); ++i) {
    if (!kFileOptions.count(args[i])) continue;
    std::stringstream in(args[i + 1]);
    std::string item, out;
    while (std::getline(in, item, ',')) out += (out.empty() ? "" : ",") + std::filesystem::absolute(item).string();
    args[i + 1] = out;
  }
  return args;
}

class TraciBackend : public ApiBackend {
 public:
  TraciBackend(std::string binary, int port, int order) : binary_(std::move(binary)), port_(port), order_(order) {}
  ~TraciBackend() override { close(); }

  void start(const std::vector<std::string>& args) override
  {
    if (running_) close();
    anchor_.clear();
    dt_ = 0;
    requested_ = false;
    // A write to a socket whose sumo died raises SIGPIPE, which would kill the whole
    // process without a word: ignore it (unless the host program installed a handler), so
    // the write fails and the loss is reported as an error like any other.
    struct sigaction old {};
    if (::sigaction(SIGPIPE, nullptr, &old) == 0 && old.sa_handler == SIG_DFL) std::signal(SIGPIPE, SIG_IGN);
    if (port_ > 0) {
      try {
        guarded("connect", [&] { api::Simulation::init(port_, kRetries); });
      } catch (const SumoError& e) {
        // libtraci's own word for "nobody listens" is "send failed: Broken pipe".
        throw SumoError(std::string(e.what()) + " (no SUMO answered on port " + std::to_string(port_) + " for " +
                        std::to_string(kRetries) + " s: start sumo --remote-port " + std::to_string(port_) + " first)");
      }
      if (order_ > 0) guarded("setOrder", [&] { api::Simulation::setOrder(order_); });
      guarded("load", [&] { api::Simulation::load(absolute_files(args)); });
    } else {
      std::vector<std::string> cmd{binary_};
      // libtraci joins the command into one line for a shell (popen): an output folder
      // `o/x;touch${IFS}y` ran `touch`, `o/run(1)` broke the start. Only characters a shell
      // takes literally pass (and any non-ASCII byte: UTF-8 names).
      auto literal = [](unsigned char c) {
        return std::isalnum(c) || c >= 0x80 || std::strchr("_./:,=+@%-", c) != nullptr;
      };
      for (const std::string& a : args) {
        for (unsigned char c : a)
          if (!literal(c))
            throw SumoError("SUMO start: argument '" + a + "' contains '" + std::string(1, static_cast<char>(c)) +
                            "', which libtraci would hand to a shell (use a path of letters, digits and _./:,=+@%-)");
        cmd.push_back(a);
      }
      guarded("start", [&] { api::Simulation::start(cmd, -1, kRetries); });
    }
    running_ = true;
  }
  std::string name() const override { return "traci"; }

  // One context subscription on a junction with a range covering any net: SUMO sends the
  // lane and position of every vehicle with the response of the next step only (the
  // subscription's time window is that step), so a tick costs one extra round trip
  // instead of two per AGV.
  void request_poses() override
  {
    call("Junction.subscribeContext", [&] {
      if (anchor_.empty()) anchor_ = api::Junction::getIDList().at(0);
      if (dt_ <= 0) dt_ = api::Simulation::getDeltaT();
      const double t = api::Simulation::getTime() + dt_;
      api::Junction::subscribeContext(anchor_, libsumo::CMD_GET_VEHICLE_VARIABLE, 1e9,
                                      {libsumo::VAR_LANE_ID, libsumo::VAR_LANEPOSITION, libsumo::VAR_SPEED}, t - dt_ / 2, t + dt_ / 2);
    });
    requested_ = true;
  }
  std::vector<VehiclePose> poses(const std::vector<std::string>& ids) override
  {
    if (!requested_) return ApiBackend::poses(ids);
    requested_ = false;
    const libsumo::SubscriptionResults all =
        call("Junction.getContextSubscriptionResults", [&] { return api::Junction::getContextSubscriptionResults(anchor_); });
    std::vector<VehiclePose> out(ids.size());
    for (size_t i = 0; i < ids.size(); ++i) {
      auto it = all.find(ids[i]);
      if (it == all.end()) continue;  // not in the network: empty lane
      const libsumo::TraCIResults& r = it->second;
      auto lane = r.find(libsumo::VAR_LANE_ID), pos = r.find(libsumo::VAR_LANEPOSITION), v = r.find(libsumo::VAR_SPEED);
      if (lane == r.end() || pos == r.end() || v == r.end())
        throw SumoError("SUMO context subscription: no lane/position/speed for " + ids[i]);
      out[i].lane = static_cast<const libsumo::TraCIString&>(*lane->second).value;
      out[i].pos = static_cast<const libsumo::TraCIDouble&>(*pos->second).value;
      out[i].speed = static_cast<const libsumo::TraCIDouble&>(*v->second).value;
    }
    return out;
  }

 private:
  // libtraci retries a refused connection once per second; sumo listens as soon as the
  // net is loaded, so a child that is not up after this long has failed to start.
  static constexpr int kRetries = 15;
  std::string binary_;
  int port_ = 0;
  int order_ = 0;          // TraCI client order (several clients), 0: the only client
  std::string anchor_;     // junction of the pose subscription
  double dt_ = 0;          // step length
  bool requested_ = false;
};

}  // namespace

std::unique_ptr<SumoBackend> make_traci_backend(const std::string& binary, int port, int order)
{
  return std::make_unique<TraciBackend>(binary, port, order);
}

}  // namespace controller
