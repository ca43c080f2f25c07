#pragma once
// SumoBackend: the few SUMO calls the controller needs, behind one interface so the same
// loop runs embedded (libsumo) or over a socket (libtraci). libsumo and libtraci headers
// cannot share a translation unit, hence one .cpp per implementation.
//
// Every call throws SumoError (one line) on failure, including a lost TraCI connection.
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace controller {

struct VehiclePose {
  std::string lane;  // "" if the vehicle is not (or no longer) in the network
  double pos = 0;    // lane position of the front
  double speed = 0;  // m/s driven in the last step (the closed loop starts from it)
};

class SumoBackend {
 public:
  // set_angle's moveToXY map-matches its point against every lane within this radius
  // (matchThreshold; SUMO's default, 100 m, cost 2-6 ms a call on the 1000-AGV warehouse
  // and made pibt-rot runs there 1-4 s per tick). The point is on the AGV's own lane (1 cm
  // off at most) and that lane wins the match by its id whatever else lies near, so a metre
  // finds the same lane at the same position: only fewer far lanes are scored. 0.1 m (10x
  // the 1 cm the point may lie off the lane): the lane search (libsumo
  // collectObjectsInRange over a box of 2 x radius) finds fewer neighbours than at 1 m
  // (huge warehouse, pibt-rot: controller/README.md, "Headings", "Cost").
  static constexpr double kAngleMatchRadius = 0.1;


  virtual ~SumoBackend() = default;

  // Starts a simulation with SUMO command-line options (without the binary name).
  virtual void start(const std::vector<std::string>& args) = 0;
  virtual void close() = 0;
  virtual bool running() const = 0;

  virtual void step() = 0;       // one SUMO step (step-length seconds)
  virtual double time() = 0;     // simulation time in seconds

  virtual void add_route(const std::string& id, const std::vector<std::string>& edges) = 0;
  // Inserted at the next step with the front at `pos` on lane `lane_index` and speed 0.
  virtual void add_vehicle(const std::string& id, const std::string& route, const std::string& type,
                           int lane_index, double pos) = 0;
  virtual void set_speed_mode(const std::string& id, int mode) = 0;
  virtual void set_speed(const std::string& id, double speed) = 0;
  virtual void set_route(const std::string& id, const std::vector<std::string>& edges) = 0;
  // To a route added with add_route: unlike set_route, SUMO does not prepend the edges the
  // vehicle has passed (its route does not grow with the run).
  virtual void set_route_id(const std::string& id, const std::string& route) = 0;
  virtual void move_to(const std::string& id, const std::string& lane, double pos) = 0;
  // Shows a vehicle standing with its front at `pos` on `lane` (of `edge`) at `angle` (SUMO
  // degrees: 0 north, 90 east) in the next step: moveTo(lane, back) now, then moveToXY(edge,
  // x/y of pos + (dx, dy), angle, keepRoute 0). Measured on SUMO 1.15 (controller/README.md
  // "Headings"): the angle holds for that step only (then the lane's again); a front at a
  // lane's very end lands 1 mm (POSITION_EPS) back; the route becomes just `edge` (set it
  // again before the following step); and SUMO takes the vehicle's speed from the distance
  // along its route from where it stands -- a point the smallest bit behind reads as a lap
  // of the route (6-16 m in one step: SUMO then reported collisions), hence `back`, a
  // little behind the point moveToXY lands on. The point lies on `lane` (within dx, dy), so
  // moveToXY looks for lanes only within kAngleMatchRadius of it (below).
  virtual void set_angle(const std::string& id, const std::string& lane, const std::string& edge, double pos,
                         double back, double angle, double dx, double dy) = 0;
  virtual double angle(const std::string& id) = 0;  // SUMO degrees
  virtual VehiclePose pose(const std::string& id) = 0;
  // Many poses at once. Call request_poses() before the step after which poses() reads
  // them: a back end may batch the read (TraCI: one context subscription answered with
  // that step, instead of two round trips per vehicle). A vehicle not in the network gets
  // an empty lane. The default reads them one by one.
  virtual void request_poses() {}
  virtual std::vector<VehiclePose> poses(const std::vector<std::string>& ids)
  {
    std::vector<VehiclePose> out;
    out.reserve(ids.size());
    for (const std::string& id : ids) out.push_back(pose(id));
    return out;
  }
  virtual void remove(const std::string& id) = 0;

  virtual std::vector<std::string> vehicles() = 0;     // in the network now
  virtual std::vector<std::string> pending() = 0;      // added, not yet inserted
  // Events of the last step:
  virtual std::vector<std::string> arrived() = 0;
  virtual std::vector<std::string> teleported() = 0;   // started teleporting
  virtual std::vector<std::string> colliding() = 0;

  virtual std::string name() const = 0;

  // The vehicle classes a lane allows now (empty: every class): lane permissions another
  // TraCI client may change at run time (rules.hpp polls them).
  virtual std::vector<std::string> lane_allowed(const std::string& lane) = 0;
  // The classes it disallows: SUMO answers getAllowed with () both for "all" and for "none"
  // (setDisallowed(lane, ['all'])), so a lane closed to every class shows only here.
  virtual std::vector<std::string> lane_disallowed(const std::string& lane) = 0;

  // What a person sees (fleet_view.hpp): a vehicle's colour, and outline polygons drawn at
  // their real size under the vehicles, with a type (sumo-gui can show it).
  using Shape = std::vector<std::pair<double, double>>;  // x/y points, closed by SUMO
  virtual void set_color(const std::string& id, int r, int g, int b, int a) = 0;
  virtual void add_polygon(const std::string& id, const std::string& type, const Shape& shape, int r, int g, int b,
                           double line_width) = 0;
  virtual void set_polygon_shape(const std::string& id, const Shape& shape) = 0;
};

// Embedded SUMO in this process (one simulation per process).
std::unique_ptr<SumoBackend> make_libsumo_backend();

// TraCI: starts `binary` (sumo or sumo-gui, found on PATH) as a child process, or, with
// port > 0, connects to a SUMO already listening there (start() then ignores args).
// order > 0: SUMO serves several clients (sumo --num-clients N); this one takes that place
// in each step's order (TraCI setOrder), and SUMO steps when every client has asked.
std::unique_ptr<SumoBackend> make_traci_backend(const std::string& binary = "sumo", int port = 0, int order = 0);

}  // namespace controller
