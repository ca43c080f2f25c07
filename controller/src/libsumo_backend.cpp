// LibsumoBackend: SUMO embedded in this process. The fastest back end (a getter costs
// ~0.5 us instead of ~12-40 us over TraCI), but libsumo keeps one global simulation per
// process and is not thread-safe: all calls come from the control loop's thread.
#include <libsumo/libsumo.h>

#include <cstdio>

#include "controller/sumo_backend.hpp"
#include "controller/sumo_error.hpp"

namespace controller {
namespace {

namespace api = libsumo;
constexpr bool kOverSocket = false;
#include "backend_impl.ipp"

class LibsumoBackend : public ApiBackend {
 public:
  ~LibsumoBackend() override { close(); }

  void start(const std::vector<std::string>& args) override
  {
    if (running_) close();
    guarded("load", [&] { api::Simulation::load(args); });
    running_ = true;
  }
  std::string name() const override { return "libsumo"; }
};

}  // namespace

std::unique_ptr<SumoBackend> make_libsumo_backend() { return std::make_unique<LibsumoBackend>(); }

}  // namespace controller
