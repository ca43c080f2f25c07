// Shared body of the two SUMO back ends. Included by libsumo_backend.cpp with
// `namespace api = libsumo` and by traci_backend.cpp with `namespace api = libtraci`:
// the two APIs have the same static functions, but their headers cannot share a
// translation unit. Lives in an anonymous namespace of each including file, which also
// defines `constexpr bool kOverSocket` (true for libtraci).

std::string one_line(std::string s)
{
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s.empty() ? "unknown error (SUMO gave no message)" : s;
}

// Runs a SUMO call; any exception becomes one SumoError line naming the call.
template <class F>
auto guarded(const char* what, F&& f) -> decltype(f())
{
  try {
    return f();
  } catch (const std::exception& e) {
    throw SumoError(std::string("SUMO ") + what + ": " + one_line(e.what()));
  }
}

class ApiBackend : public SumoBackend {
 public:
  bool running() const override { return running_; }
  void close() override
  {
    if (!running_) return;
    running_ = false;
    try {
      api::Simulation::close();
    } catch (const std::exception&) {
      // A broken simulation or a lost connection: nothing left to report.
    }
  }

  void step() override
  {
    call("step", [] { api::Simulation::step(); });
  }
  double time() override
  {
    return call("getTime", [] { return api::Simulation::getTime(); });
  }
  void add_route(const std::string& id, const std::vector<std::string>& edges) override
  {
    call("Route.add", [&] { api::Route::add(id, edges); });
  }
  void add_vehicle(const std::string& id, const std::string& route, const std::string& type, int lane_index,
                   double pos) override
  {
    call("Vehicle.add", [&] {
      api::Vehicle::add(id, route, type, "now", std::to_string(lane_index), fmt(pos), "0");
    });
  }
  void set_speed_mode(const std::string& id, int mode) override
  {
    call("Vehicle.setSpeedMode", [&] { api::Vehicle::setSpeedMode(id, mode); });
  }
  void set_speed(const std::string& id, double speed) override
  {
    call("Vehicle.setSpeed", [&] { api::Vehicle::setSpeed(id, speed); });
  }
  void set_route(const std::string& id, const std::vector<std::string>& edges) override
  {
    call("Vehicle.setRoute", [&] { api::Vehicle::setRoute(id, edges); });
  }
  void set_route_id(const std::string& id, const std::string& route) override
  {
    call("Vehicle.setRouteID", [&] { api::Vehicle::setRouteID(id, route); });
  }
  void move_to(const std::string& id, const std::string& lane, double pos) override
  {
    call("Vehicle.moveTo", [&] { api::Vehicle::moveTo(id, lane, pos); });
  }
  void set_angle(const std::string& id, const std::string& lane, const std::string& edge, double pos, double back,
                 double angle, double dx, double dy) override
  {
    call("Vehicle.moveToXY", [&] {
      const libsumo::TraCIPosition p = api::Simulation::convert2D(edge, pos, 0);
      api::Vehicle::moveTo(id, lane, back);
      api::Vehicle::moveToXY(id, edge, 0, p.x + dx, p.y + dy, angle, 0, kAngleMatchRadius);
    });
  }
  double angle(const std::string& id) override
  {
    return call("Vehicle.getAngle", [&] { return api::Vehicle::getAngle(id); });
  }
  VehiclePose pose(const std::string& id) override
  {
    return call("Vehicle.getLaneID/getLanePosition/getSpeed", [&] {
      return VehiclePose{api::Vehicle::getLaneID(id), api::Vehicle::getLanePosition(id), api::Vehicle::getSpeed(id)};
    });
  }
  void remove(const std::string& id) override
  {
    call("Vehicle.remove", [&] { api::Vehicle::remove(id); });
  }
  std::vector<std::string> vehicles() override
  {
    return call("Vehicle.getIDList", [] { return api::Vehicle::getIDList(); });
  }
  std::vector<std::string> pending() override
  {
    return call("Simulation.getPendingVehicles", [] { return api::Simulation::getPendingVehicles(); });
  }
  std::vector<std::string> arrived() override
  {
    return call("Simulation.getArrivedIDList", [] { return api::Simulation::getArrivedIDList(); });
  }
  std::vector<std::string> teleported() override
  {
    return call("Simulation.getStartingTeleportIDList", [] { return api::Simulation::getStartingTeleportIDList(); });
  }
  std::vector<std::string> colliding() override
  {
    return call("Simulation.getCollidingVehiclesIDList", [] { return api::Simulation::getCollidingVehiclesIDList(); });
  }
  std::vector<std::string> lane_allowed(const std::string& lane) override
  {
    return call("Lane.getAllowed", [&] { return api::Lane::getAllowed(lane); });
  }
  std::vector<std::string> lane_disallowed(const std::string& lane) override
  {
    return call("Lane.getDisallowed", [&] { return api::Lane::getDisallowed(lane); });
  }
  void set_color(const std::string& id, int r, int g, int b, int a) override
  {
    call("Vehicle.setColor", [&] { api::Vehicle::setColor(id, libsumo::TraCIColor(r, g, b, a)); });
  }
  void add_polygon(const std::string& id, const std::string& type, const Shape& shape, int r, int g, int b,
                   double line_width) override
  {
    // Layer 10: above the lanes, below the vehicles (sumo-gui draws by layer).
    call("Polygon.add",
         [&] { api::Polygon::add(id, positions(shape), libsumo::TraCIColor(r, g, b, 255), false, type, 10, line_width); });
  }
  void set_polygon_shape(const std::string& id, const Shape& shape) override
  {
    call("Polygon.setShape", [&] { api::Polygon::setShape(id, positions(shape)); });
  }

 protected:
  // A call on a running simulation. libtraci dereferences a null connection once it is
  // closed, so nothing goes through after a close or a fatal (connection) error.
  template <class F>
  auto call(const char* what, F&& f) -> decltype(f())
  {
    if (!running_) throw SumoError(std::string("SUMO ") + what + ": no simulation running (closed or connection lost)");
    try {
      return f();
    } catch (const libsumo::TraCIException& e) {
      // SUMO refused the call (unknown vehicle, bad lane, ...): the simulation goes on.
      throw SumoError(std::string("SUMO ") + what + ": " + one_line(e.what()));
    } catch (const libsumo::FatalTraCIError& e) {
      running_ = false;
      throw SumoError(std::string("SUMO ") + what + ": connection lost: " + one_line(e.what()));
    } catch (const std::exception& e) {
      // Over a socket anything else is the transport (tcpip::SocketException: sumo died,
      // broken pipe, reset); embedded it is SUMO's own ProcessError.
      if (!kOverSocket) throw SumoError(std::string("SUMO ") + what + ": " + one_line(e.what()));
      running_ = false;
      throw SumoError(std::string("SUMO ") + what + ": connection lost: " + one_line(e.what()));
    }
  }

  bool running_ = false;

  static libsumo::TraCIPositionVector positions(const Shape& shape)
  {
    libsumo::TraCIPositionVector v;
    for (const auto& [x, y] : shape) {
      libsumo::TraCIPosition p;
      p.x = x;
      p.y = y;
      v.value.push_back(p);
    }
    return v;
  }

  // Exact decimal of a double: SUMO parses departPos as text.
  static std::string fmt(double x)
  {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
  }
};
