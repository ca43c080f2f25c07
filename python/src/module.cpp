// rtlacam._rtlacam: the planner, the learned policy and lifelong runs for Python.
// Configurations are lists of vertex ids (planner::Config <-> list[int]); no numpy needed.
// Objects that C++ holds by reference (a planner's Graph, a policy's Model) are kept
// alive from Python with keep_alive, so no call can outlive what it points to.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <climits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>
#include <unordered_map>

#include "planner/error.hpp"
#include "planner/highways.hpp"
#include "planner/movingai.hpp"
#include "planner/plan_io.hpp"
#include "planner/lacam/runner.hpp"
#include "planner/rotation/traffic_flow.hpp"
#include "planner/rotation_settings.hpp"
#include "planner/solver.hpp"
#include "planner/validator.hpp"
#include "policy/policy_preference.hpp"
#include "policy/weights_file.hpp"
#include "tasks/lifelong_log.hpp"
#include "tasks/lifelong_runner.hpp"
#include "tasks/lorr_instance.hpp"
#include "tasks/task_layer.hpp"

namespace py = pybind11;
using namespace planner;

namespace {

// A number argument: TypeError unless int or float (a str cast would raise RuntimeError),
// ValueError unless finite and in [lo, hi] (NaN passes every comparison, and a negative or
// infinite budget or limit would run unbounded).
double finite_arg(const py::handle& x, const char* name, double lo, double hi)
{
  if (!(py::isinstance<py::float_>(x) || py::isinstance<py::int_>(x)) || py::isinstance<py::bool_>(x))
    throw py::type_error(std::string(name) + ": expected a number, not " + std::string(py::str(py::type::of(x))));
  const double v = x.cast<double>();
  if (!(v >= lo && v <= hi))
    throw py::value_error(std::string(name) + ": " + std::string(py::repr(x)) + " is out of range [" +
                          std::string(py::repr(py::float_(lo))) + ", " + std::string(py::repr(py::float_(hi))) + "]");
  return v;
}

// A budget from keyword arguments: wall clock and/or expansions (both none: unlimited).
// Called with the GIL held: casting (and raising for) a bad argument needs it; search()
// used to convert after releasing it and segfaulted on expansions=-1 or time_ms="x".
Budget make_budget(const py::object& time_ms, const py::object& expansions)
{
  Budget b = Budget::unlimited();
  if (!time_ms.is_none()) b.ms = finite_arg(time_ms, "time_ms", 0, 1e10);
  if (!expansions.is_none()) {
    if (!py::isinstance<py::int_>(expansions) || py::isinstance<py::bool_>(expansions))
      throw py::type_error("expansions: expected an integer, not " + std::string(py::str(py::type::of(expansions))));
    try {
      b.expansions = expansions.cast<uint64_t>();
    } catch (const py::cast_error&) {
      throw py::value_error("expansions: " + std::string(py::repr(expansions)) + " is out of range [0, 2**64 - 1]");
    }
  }
  return b;
}

// A configuration for `g` and `n` agents (n < 0: any length): ValueError naming `what`
// and the agent, as make_planner and the scen loader check; planners, the validator and
// the policy index tables with these vertices unchecked.
void check_config(const Graph& g, const Config& c, int n, const std::string& what)
{
  if (n >= 0 && static_cast<int>(c.size()) != n)
    throw std::invalid_argument(what + ": " + std::to_string(c.size()) + " vertices for " + std::to_string(n) + " agents");
  for (size_t i = 0; i < c.size(); ++i)
    if (c[i] < 0 || c[i] >= g.size())
      throw std::invalid_argument(what + ": agent " + std::to_string(i) + "'s vertex " + std::to_string(c[i]) +
                                  " is out of range (the graph has " + std::to_string(g.size()) + " vertices)");
}

// Two agents on one vertex: ValueError naming both (load_scen's check; the planners assume
// distinct starts and silently planned from a vertex conflict).
void check_distinct(const Config& c, const std::string& what)
{
  std::unordered_map<Vertex, size_t> seen;
  for (size_t i = 0; i < c.size(); ++i)
    if (auto [it, fresh] = seen.emplace(c[i], i); !fresh)
      throw std::invalid_argument(what + ": agents " + std::to_string(it->second) + " and " + std::to_string(i) +
                                  " share vertex " + std::to_string(c[i]));
}

// highways= : None is the CLI's default (default_highways), else a penalty in [0, 200].
int read_highways(const py::object& h, Solver s, bool refine)
{
  if (h.is_none()) return default_highways(s, refine);
  const int p = h.cast<int>();
  if (p < 0 || p > 200) throw std::invalid_argument("highways must be in [0, 200]");
  return p;
}

// JSON -> Python objects through the json module (the log is small; one copy is fine).
py::object to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

py::dict run_result(const RunResult& r)
{
  py::dict d;
  d["solved"] = r.solved;
  d["no_solution"] = r.no_solution;
  d["timed_out"] = r.timed_out;
  d["step_limit"] = r.step_limit;
  d["valid"] = r.validation_error.empty();
  d["validation_error"] = r.validation_error;
  d["total_planning_ms"] = r.total_planning_ms;
  d["max_iteration_ms"] = r.max_iteration_ms;
  d["p99_iteration_ms"] = r.p99_iteration_ms;
  d["iterations"] = r.iterations;
  d["soc"] = r.soc;  // standard (last arrival), as the CLI
  d["sum_of_loss"] = r.sum_of_loss;
  d["makespan"] = r.makespan;
  d["expansions"] = r.expansions;
  d["explored"] = r.explored;
  d["plan"] = r.plan;
  return d;
}

// A dict argument's keys, each handed to `set` (unknown keys: InputError naming `what`).
template <class Set>
void each_key(const py::object& d, const std::string& what, Set set)
{
  for (const auto& [k, v] : d.cast<py::dict>()) {
    const std::string key = py::str(k);
    if (!set(key, v)) throw InputError(what + ": unknown key '" + key + "'");
  }
}

// rotation= on top of `s` for `kind`: a dict of the SUMO YAML's planner.rotation keys
// (planner/rotation_settings.hpp). An unknown key, a key `kind` does not read, a wrong type or
// a value out of range is an InputError naming the key ("rotation.window: only with solver
// wppl, not epibt").
void read_rotation(const py::object& d, Solver kind, RotationSettings& s)
{
  if (d.is_none()) return;
  if (!plans_rotation(kind))
    throw InputError(std::string("rotation: only with a rotation solver (pibt-rot | epibt | wppl), not ") + to_string(kind));
  if (!py::isinstance<py::dict>(d)) throw InputError("rotation: expected a dict of planner.rotation's keys");
  const std::vector<std::string>& keys = rotation_keys();
  bool costs = false;
  for (const auto& [k, v] : d.cast<py::dict>()) {
    const std::string key = py::str(k);
    const std::string at = "rotation." + key;
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
      std::string names;
      for (const std::string& n : keys) names += (names.empty() ? "" : " | ") + n;
      throw InputError("rotation: unknown key '" + key + "' (" + names + ")");
    }
    if (std::string why = rotation_key_misuse(kind, key); !why.empty()) throw InputError(at + ": " + why);
    auto integer = [&](const py::handle& x, const std::string& where) {
      if (!py::isinstance<py::int_>(x) || py::isinstance<py::bool_>(x)) throw InputError(where + ": expected an integer");
      long long n = 0;
      try {
        n = x.cast<long long>();
      } catch (const py::cast_error&) {
        n = LLONG_MAX;
      }
      if (n < INT_MIN || n > INT_MAX) throw InputError(where + ": " + std::string(py::str(x)) + " is out of range");
      return static_cast<int>(n);
    };
    auto flag = [&]() {
      if (!py::isinstance<py::bool_>(v)) throw InputError(at + ": expected True or False");
      return v.cast<bool>();
    };
    auto text = [&]() {
      if (!py::isinstance<py::str>(v)) throw InputError(at + ": expected a string");
      return v.cast<std::string>();
    };
    if (key == "back_last") s.back_last = flag();
    else if (key == "guidance") s.guidance = text();
    else if (key == "guidance_costs") {
      if (!(py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) || py::len(v) != 3)
        throw InputError(at + ": expected [along, against, turn]");
      const py::sequence c = v.cast<py::sequence>();
      for (size_t i = 0; i < 3; ++i) s.guidance_costs[i] = integer(c[i], at + "[" + std::to_string(i) + "]");
      costs = true;
    } else if (key == "traffic_flow") s.traffic_flow = flag();
    else if (key == "depth") s.depth = integer(v, at);
    else if (key == "lns_rounds") s.lns_rounds = integer(v, at);
    else if (key == "revisit") s.revisit = integer(v, at);
    else if (key == "priority") s.priority = text();
    else if (key == "pocket_exit") s.pocket_exit = flag();
    else if (key == "leavers_first") s.leavers_first = flag();
    else if (key == "window") s.window = integer(v, at);
    else if (key == "neighbourhood") s.neighbourhood = integer(v, at);
  }
  if (costs && s.guidance != "arrows") throw InputError("rotation.guidance_costs: only with guidance 'arrows'");
  if (std::string e = check(s); !e.empty()) throw InputError("rotation." + e);
}

// `s` into `so` for a rotation solver; nothing for a cell solver. InputError as read_rotation.
void apply_rotation(Solver kind, const RotationSettings& s, const Graph& g, SolverOptions& so)
{
  if (!plans_rotation(kind)) return;
  try {
    apply(s, g, so);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("rotation.") + e.what());
  }
}

// The task layer from keyword arguments (tasks/task_layer.hpp), with the YAML's names:
// queues = tasks.queues, urgency = tasks.urgency, parking = tasks.parking (cell ids),
// battery = fleet.battery (+ charge_w, on `chargers`, as rtlacam-lifelong --battery-*).
tasks::TaskLayerOptions task_layer(const tasks::LorrProblem& pr, const std::string& mode, const std::string& assigner,
                                   int pool_size, int k_nearest, bool reassign, const py::object& queues,
                                   const py::object& urgency, const py::object& parking, const py::object& battery,
                                   const std::vector<Vertex>& chargers, const std::string& solver)
{
  tasks::TaskLayerOptions o;
  o.queues.in_line = tasks::in_line_by_default(solver);
  o.mode = mode.empty() ? pr.default_mode() : mode;
  o.assigner = assigner;
  o.pool_size = pool_size > 0 ? pool_size : pr.pool_size();
  o.k_nearest = k_nearest;
  o.reassign = reassign;
  if (!queues.is_none())
    each_key(queues, "queues", [&](const std::string& k, const py::handle& v) {
      if (k == "capacity") o.queues.capacity = v.cast<int>();
      else if (k == "length") o.queues.length = v.cast<int>();
      else if (k == "admission") o.queues.admission = v.cast<int>();
      else if (k == "fifo") o.queues.fifo = v.cast<bool>();
      else if (k == "in_line") o.queues.in_line = v.cast<bool>();
      else if (k == "leavers_first") o.queues.leavers_first = v.cast<bool>();
      else if (k == "one_way") o.queues.one_way = v.cast<bool>();
      else if (k == "clear_after") {
        const int n = v.cast<int>();
        if (n < 0) throw InputError("queues.clear_after: must be >= 0, not " + std::to_string(n));
        o.queues.clear_after = n;
      } else if (k == "jam_after") {
        const int n = v.cast<int>();
        if (n < 0) throw InputError("queues.jam_after: must be >= 0, not " + std::to_string(n));
        o.queues.jam_after = n;
      } else return false;
      return true;
    });
  if (o.queues.leavers_first && o.queues.clear_after == 0)
    throw InputError("queues.leavers_first: needs clear_after > 0 (it acts while a station clears its pocket)");
  if (!urgency.is_none())
    each_key(urgency, "urgency", [&](const std::string& k, const py::handle& v) {
      if (k == "stalls" && py::isinstance<py::str>(v)) {
        // "auto": on with station queues (the YAML's default, tasks.urgency.stalls).
        if (v.cast<std::string>() != "auto") throw InputError("urgency.stalls: True, False or 'auto'");
        o.urgency.stalls = o.queues.on();
      } else if (k == "stalls") o.urgency.stalls = v.cast<bool>();
      else if (k == "battery") o.urgency.battery = v.cast<bool>();
      else if (k == "drop_hints") o.urgency.drop_hints = v.cast<bool>();
      else if (k == "sticky") o.urgency.sticky = v.cast<bool>();
      else if (k == "swap_after" || k == "head_after" || k == "load_cost" || k == "pocket_cost" || k == "escalate_after") {
        const int n = v.cast<int>();
        if (n < 0) throw InputError("urgency." + k + ": must be >= 0, not " + std::to_string(n));
        (k == "swap_after"   ? o.urgency.swap_after
         : k == "head_after" ? o.urgency.head_after
         : k == "load_cost"  ? o.urgency.load_cost
         : k == "escalate_after" ? o.urgency.escalate_after
                             : o.urgency.pocket_cost) = n;
      } else return false;
      return true;
    });
  if (!parking.is_none()) o.parking = {true, parking.cast<std::vector<Vertex>>()};
  if (!battery.is_none()) {
    // rtlacam-lifelong's --battery-* options, under the YAML names of fleet.battery.
    o.battery.on = true;
    o.battery.charger_cells = chargers;
    tasks::BatteryOptions& b = o.battery.options;
    each_key(battery, "battery", [&](const std::string& k, const py::handle& v) {
      if (k == "charging") b.charging = v.cast<bool>();
      else if (k == "capacity_wh") b.capacity_wh = v.cast<double>();
      else if (k == "initial") b.initial = v.cast<double>();
      else if (k == "per_m_wh") b.per_m_wh = v.cast<double>();
      else if (k == "per_turn_wh") b.per_turn_wh = v.cast<double>();
      else if (k == "threshold") b.threshold = v.cast<double>();
      else if (k == "critical") b.critical = v.cast<double>();
      else if (k == "reserve_margin") b.reserve_margin = v.cast<double>();
      else if (k == "rematch") b.rematch = v.cast<bool>();
      else if (k == "task_check") b.task_check = v.cast<bool>();
      else if (k == "target") b.target = v.cast<double>();
      else if (k == "charge_w") o.battery.charge_w = v.cast<double>();
      else return false;
      return true;
    });
  } else if (!chargers.empty()) {
    throw InputError("chargers: only with battery={...}");
  }
  return o;
}

// The lifelong runner on a LoRR problem, as rtlacam-lifelong runs it; returns its JSON log.
py::object lifelong(const std::string& problem_file, const std::string& solver, long steps, double budget_ms,
                    uint64_t budget_expansions, const std::string& mode, const std::string& assigner, uint64_t seed,
                    int agents, bool reassign, const std::string& policy_file, const py::object& battery,
                    const std::vector<Vertex>& chargers, int pool_size, int k_nearest, const py::object& queues,
                    const py::object& urgency, const py::object& parking, const std::optional<std::string>& action_model,
                    const py::object& rotation, int highways)
{
  using namespace tasks;
  // As rtlacam-lifelong's option checks: NaN, a negative count or a negative step count was
  // taken silently (agents=-1: the whole team; steps=-5: "no simulation_time.json entry").
  if (!(budget_ms >= 0 && budget_ms <= 3.6e6))
    throw py::value_error("budget_ms: " + std::string(py::repr(py::float_(budget_ms))) + " is out of range [0, 3600000]");
  if (agents < 0) throw py::value_error("agents: must be >= 0 (0: the problem's teamSize), not " + std::to_string(agents));
  if (steps < -1)
    throw py::value_error("steps: must be >= 0 (-1: the problem's simulation_time.json entry), not " + std::to_string(steps));
  if (pool_size < 0) throw py::value_error("pool_size: must be >= 0 (0: the problem's), not " + std::to_string(pool_size));
  if (highways < 0 || highways > 1000) throw py::value_error("highways: must be in [0, 1000], not " + std::to_string(highways));
  // Naming a rotation solver is enough: the action model follows from it (issue 20).
  const Solver kind = parse_solver(solver);
  const std::string actions = action_model ? *action_model : plans_rotation(kind) ? "rotation" : "grid4";
  // rtlacam-lifelong --highways (apps/lifelong_cli.hpp): off by default in lifelong runs.
  if (highways > 0 && kind != Solver::RtLacam && kind != Solver::Naive)
    throw InputError("highways needs solver rtlacam or naive (a LaCAM planner)");
  if (actions != "grid4" && actions != "rotation")
    throw InputError("action_model: must be 'grid4' or 'rotation', not '" + actions + "'");
  if (plans_rotation(kind) && actions == "grid4")
    throw InputError("action_model 'grid4': solver " + solver + " plans rotation actions (leave action_model out, or 'rotation')");
  RotationSettings rs = RotationSettings::lifelong(kind);  // rtlacam-lifelong's defaults
  read_rotation(rotation, kind, rs);
  const LorrInstance in = load_lorr_instance(problem_file, agents, "agents=");
  const LorrProblem& pr = in.problem;
  const Config& starts = in.starts;
  if (steps < 0) steps = pr.simulation_time;
  if (steps < 0) throw input_error(problem_file, 0, "no simulation_time.json entry for this problem: pass steps=");
  const TaskLayerOptions layer =
      task_layer(pr, mode, assigner, pool_size, k_nearest, reassign, queues, urgency, parking, battery, chargers, solver);
  // queues one_way: the run plans on the one-way queue lanes (tasks/station_queues.hpp).
  const Graph g = [&] {
    if (!layer.queues.on() || !layer.queues.one_way) return in.g;
    try {
      return one_way_queue_lanes(in.g, in.tasks->errand_cells(), layer.queues);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("queues.one_way: ") + e.what());
    }
  }();
  std::unique_ptr<TaskManager> tm;
  try {
    tm = make_task_layer(in.tasks, g, layer);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();  // the YAML's key names; mode is tasks.assignment there
    throw InputError(what.rfind("assignment:", 0) == 0 ? "mode" + what.substr(10) : what);
  }
  policy::Model model;
  std::unique_ptr<policy::PolicyPreference> pref;
  if (!policy_file.empty()) {
    model = policy::load_weights(policy_file);
    pref = std::make_unique<policy::PolicyPreference>(g, model, Config{});
  }
  LifelongOptions opt;
  opt.solver.pref = pref.get();
  apply_rotation(kind, rs, g, opt.solver);
  opt.solver.lacam.highways = highways;
  opt.action_model = parse_action_model(actions);
  opt.steps = steps;
  opt.budget = Budget::time_ms(budget_ms);
  if (budget_expansions > 0) opt.budget.expansions = budget_expansions;
  LifelongResult r;
  {
    py::gil_scoped_release unlocked;  // a long run: let other Python threads go on
    r = run_lifelong(g, starts, *tm, solver, seed, opt);
  }
  nlohmann::json j = lifelong_log(RunInfo{problem_file, solver, layer.mode, assigner, pr.team_size, budget_ms, seed}, r);
  if (pref) j["policy"] = policy_file;
  if (highways > 0) j["highways"] = highways;
  // rtlacam-lifelong's solver fields (apps/lifelong_cli.hpp SolverCli::describe).
  if (plans_rotation(kind) && rs.guidance == "arrows")
    j["guidance"] = "arrows " + std::to_string(rs.guidance_costs[0]) + "," + std::to_string(rs.guidance_costs[1]) + "," +
                    std::to_string(rs.guidance_costs[2]);
  if (const TrafficFlowOptions& tf = opt.solver.epibt.tf; kind == Solver::Epibt && tf.on)
    j["trafficFlow"] = {{"active", TrafficFlow::fits(starts.size(), g.size(), tf)},
                        {"contraflow", tf.contraflow},
                        {"vertex", tf.vertex},
                        {"refresh", tf.refresh}};
  add_task_fields(j, *tm);
  add_stuck_fields(j, r);  // rtlacam-lifelong warns on stderr; here the fields say it
  return to_python(j);
}

}  // namespace

PYBIND11_MODULE(_rtlacam, m)
{
  m.doc() = "RT-LaCAM (Real-Time LaCAM, SoCS 2025): real-time MAPF planners, validator, lifelong runs";
  m.attr("__version__") = RTLACAM_VERSION;
  m.attr("SOLVERS") = solver_list();  // lacam: run() only (plans once); the others: make_planner

  // Bad input (a file:line message) is ValueError in Python; other errors RuntimeError.
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

  py::class_<Graph>(m, "Graph", "MAPF graph: dense vertex ids, undirected edges; MovingAI grids have (x, y)")
      .def_property_readonly("size", &Graph::size)
      .def("__len__", &Graph::size)
      .def_property_readonly("num_edges", &Graph::num_edges)
      .def_property_readonly("width", &Graph::width)
      .def_property_readonly("height", &Graph::height)
      .def_readonly("name", &Graph::name)
      .def("neighbors", [](const Graph& g, Vertex v) {
        if (v < 0 || v >= g.size()) throw py::index_error("vertex out of range");
        auto s = g.neighbors(v);
        return std::vector<Vertex>(s.begin(), s.end());
      })
      .def("adjacent", &Graph::adjacent)
      .def("at", &Graph::at, py::arg("x"), py::arg("y"), "vertex at column x, row y (-1: obstacle / off the map)")
      .def("xy", [](const Graph& g, Vertex v) {
        if (!g.is_grid() || v < 0 || v >= g.size()) throw py::index_error("not a grid vertex");
        return py::make_tuple(g.cell_x(v), g.cell_y(v));
      });

  py::class_<Instance>(m, "Instance", "starts and goals of the agents")
      .def_readonly("starts", &Instance::starts)
      .def_readonly("goals", &Instance::goals)
      .def_property_readonly("num_agents", &Instance::num_agents)
      .def("soc_lower_bound", &Instance::soc_lower_bound);

  m.def("load_map", &load_map, py::arg("path"), "MovingAI .map -> Graph");
  m.def(
      "highway_arcs",
      [](const Graph& g, int penalty, int min_run) {
        if (penalty < 0 || penalty > 200) throw std::invalid_argument("penalty must be in [0, 200]");
        if (min_run < 1) throw std::invalid_argument("min_run must be >= 1");
        const auto costs = highway_costs(g, HighwayOptions{penalty, min_run});
        std::vector<std::tuple<Vertex, Vertex, int>> out;
        if (costs.empty()) return out;
        for (Vertex u = 0; u < g.size(); ++u) {
          const auto in = g.in_neighbors(u);
          for (size_t k = 0; k < in.size(); ++k)
            if (const int c = costs[g.in_arc(u) + k]) out.emplace_back(in[k], u, c);
        }
        return out;
      },
      py::arg("graph"), py::arg("penalty") = 1, py::arg("min_run") = 3,
      "highways (rtlacam-bench --highways): the moves (w, u, extra) that go against a 1-wide corridor's grain "
      "and cost 1 + extra in RT-LaCAM*'s PIBT ranking; empty where no corridor run of min_run cells exists");
  m.def("load_scen", &load_scen, py::arg("path"), py::arg("graph"), py::arg("agents"),
        "first `agents` rows of a MovingAI .scen on `graph` -> Instance");

  py::class_<RealtimePlanner>(m, "Planner", "search(budget) / next() / commit() / set_goals(): see RealtimePlanner")
      .def("search", [](RealtimePlanner& p, py::object time_ms, py::object expansions) {
             const Budget b = make_budget(time_ms, expansions);  // with the GIL: it may raise
             Status s;
             {
               py::gil_scoped_release unlocked;
               s = p.search(b);
             }
             return std::string(to_string(s));
           },
           py::arg("time_ms") = py::none(), py::arg("expansions") = py::none(),
           "think for a wall-clock budget and/or a number of LaCAM expansions; returns the status")
      .def("next", &RealtimePlanner::next, "the configuration to move to now")
      .def("commit", &RealtimePlanner::commit, "the agents are there: advance (reroot)")
      .def("step", [](RealtimePlanner& p, py::object time_ms, py::object expansions) {
             return p.step(make_budget(time_ms, expansions));
           },
           py::arg("time_ms") = py::none(), py::arg("expansions") = py::none(), "search + next")
      .def("set_goals",
           [](RealtimePlanner& p, const Config& goals) {
             // The planners index their distance tables with these unchecked (segfault).
             if (const Graph* g = p.graph()) check_config(*g, goals, static_cast<int>(p.current().size()), "goals");
             p.set_goals(goals);
           },
           py::arg("goals"),
           "new goals: a new search rooted at the current configuration")
      .def("set_immobile", static_cast<void (RealtimePlanner::*)(int, bool)>(&RealtimePlanner::set_immobile), py::arg("agent"), py::arg("immobile") = true,
           "mark an agent immobile (never moved; the others route around it) or mobile again")
      .def_property_readonly("current", &RealtimePlanner::current)
      .def_property_readonly("goals", &RealtimePlanner::goals)
      .def_property_readonly("at_goal", &RealtimePlanner::at_goal)
      .def_property_readonly("exhausted", &RealtimePlanner::exhausted)
      .def_property_readonly("expansions", &RealtimePlanner::expansions)
      .def_property_readonly("explored", &RealtimePlanner::explored)
      .def_property_readonly("name", &RealtimePlanner::name);

  py::class_<policy::Model>(m, "Policy", "a learned one-step policy (weights file)");
  m.def("load_policy", &policy::load_weights, py::arg("path"));

  // The preference must outlive the planner and keep its Graph and Model alive.
  py::class_<policy::PolicyPreference>(m, "PolicyPreference")
      .def(py::init([](const Graph& g, const policy::Model& m, const Config& goals) {
             check_config(g, goals, -1, "goals");  // its distance table runs a BFS from each (segfault)
             return std::make_unique<policy::PolicyPreference>(g, m, goals);
           }),
           py::arg("graph"), py::arg("policy"), py::arg("goals"), py::keep_alive<1, 2>(), py::keep_alive<1, 3>());

  m.def("make_planner",
        [](const std::string& solver, const Graph& g, const Config& starts, const Config& goals, uint64_t seed,
           policy::PolicyPreference* pref, bool refine, const std::string& objective, const py::object& rotation,
           bool iter_refine, const py::object& highways) {
          const Solver kind = parse_solver(solver);
          RotationSettings rs;  // the planners' own defaults, as before rotation= (no guidance, no traffic flow)
          read_rotation(rotation, kind, rs);
          if (static_cast<int>(starts.size()) != static_cast<int>(goals.size()))
            throw std::invalid_argument("starts and goals differ in length");
          check_config(g, starts, -1, "starts");
          check_config(g, goals, -1, "goals");
          // As load_scen (Instance::check): one-shot MAPF needs distinct starts and goals.
          check_distinct(starts, "starts");
          check_distinct(goals, "goals");
          SolverOptions opt;
          opt.seed = seed;
          opt.pref = pref;
          opt.lacam.refine = opt.lacam.scatter = refine;  // as rtlacam-bench: RT-LaCAM* unless refine=False
          opt.lacam.free_first = refine && parse_solver(solver) == Solver::RtLacam;  // as rtlacam-bench
          opt.lacam.resumable = refine;  // the paper's: one whole expansion at least per iteration
          opt.lacam.objective = parse_objective(objective);  // rtlacam-bench --objective
          opt.lacam.iter_refine = iter_refine;               // rtlacam-bench --iter-refine
          opt.lacam.highways = read_highways(highways, kind, refine);  // rtlacam-bench --highways
          apply_rotation(kind, rs, g, opt);
          return make_planner(kind, g, starts, goals, opt);
        },
        py::arg("solver"), py::arg("graph"), py::arg("starts"), py::arg("goals"), py::arg("seed") = 0,
        py::arg("policy") = nullptr, py::arg("refine") = true, py::arg("objective") = "soc",
        py::arg("rotation") = py::none(), py::arg("iter_refine") = false, py::arg("highways") = py::none(),
        py::keep_alive<0, 2>(),
        py::keep_alive<0, 6>(),
        "solver: a name in SOLVERS but lacam (cspibt needs policy=PolicyPreference; pibt-rot, epibt, wppl plan "
        "rotation actions on a grid, every robot facing east at the start); refine=False: the paper's RT-LaCAM "
        "(rtlacam-bench --no-refine --no-resumable), else RT-LaCAM* as the CLI; objective: what refinement lowers, 'soc' "
        "(standard sum of costs) or 'loss' (sum of loss), as rtlacam-bench --objective; rotation: pibt-rot, epibt, wppl "
        "only, a dict of the SUMO YAML's planner.rotation keys (back_last, guidance: 'none' | 'arrows', guidance_costs: "
        "[along, against, turn], traffic_flow, depth, lns_rounds, revisit, priority: 'distance' | 'age', pocket_exit, "
        "leavers_first, window, neighbourhood; each only with the solver that reads it); unset keys keep the planners' "
        "own defaults (no guidance, no traffic flow; lifelong() uses rtlacam-lifelong's); iter_refine: RT-LaCAM* "
        "refines by iterative refinement instead of LNS (rtlacam-bench --iter-refine); highways: PIBT's penalty for a move "
        "against a 1-wide corridor's grain (rtlacam-bench --highways; None: 1 for RT-LaCAM*, else 0)");

  m.def("run",
        [](const std::string& solver, const Graph& g, const Instance& ins, py::object time_ms, py::object expansions,
           double timeout_ms, long long max_steps, uint64_t seed, policy::PolicyPreference* pref, bool refine,
           const std::string& objective, const py::object& iter_refine, double anytime_ms, const py::object& highways) {
          RunOptions ropt;
          ropt.per_iteration = make_budget(time_ms, expansions);
          // NaN or a negative limit was taken silently (rtlacam-bench checks its options).
          if (!(timeout_ms >= 0 && timeout_ms <= 1e10))
            throw py::value_error("timeout_ms: " + std::string(py::repr(py::float_(timeout_ms))) +
                                  " is out of range [0, 1e10]");
          if (max_steps < 0) throw py::value_error("max_steps: must be >= 0, not " + std::to_string(max_steps));
          ropt.timeout_ms = timeout_ms;
          if (!(anytime_ms >= 0 && anytime_ms <= 1e10)) throw std::invalid_argument("anytime_ms must be in [0, 1e10]");
          ropt.anytime_ms = anytime_ms;
          ropt.max_steps = max_steps;
          const Solver s = parse_solver(solver);
          SolverOptions sopt;
          sopt.seed = seed;
          sopt.lacam.seed = seed;  // run_full_horizon (lacam) reads it there
          sopt.lacam.refine = sopt.lacam.scatter = refine;  // as rtlacam-bench (lacam: executes its first solution either way)
          sopt.lacam.free_first = refine && s == Solver::RtLacam;  // as rtlacam-bench (RT-LaCAM* only)
          sopt.lacam.resumable = refine;  // the paper's: one whole expansion at least per iteration
          sopt.lacam.objective = parse_objective(objective);  // rtlacam-bench --objective
          // rtlacam-bench --iter-refine; None: its default (on for lacam with anytime_ms, else off)
          sopt.lacam.iter_refine = iter_refine.is_none() ? default_iter_refine(s, refine, anytime_ms) : iter_refine.cast<bool>();
          sopt.lacam.highways = read_highways(highways, s, refine);  // rtlacam-bench --highways
          sopt.pref = pref;
          const LacamOptions& lopt = sopt.lacam;
          std::unique_ptr<RealtimePlanner> p;
          if (is_realtime(s)) p = make_planner(s, g, ins.starts, ins.goals, sopt);
          RunResult r;
          {
            py::gil_scoped_release unlocked;
            if (p) {
              r = run_realtime(*p, g, ins.starts, ins.goals, ropt);
            } else {
              r = run_full_horizon(g, ins.starts, ins.goals, lopt, ropt, pref);
            }
          }
          return run_result(r);
        },
        py::arg("solver"), py::arg("graph"), py::arg("instance"), py::arg("time_ms") = 1.0,
        py::arg("expansions") = py::none(), py::arg("timeout_ms") = 60000.0, py::arg("max_steps") = 100000,
        py::arg("seed") = 0, py::arg("policy") = nullptr, py::arg("refine") = true, py::arg("objective") = "soc",
        py::arg("iter_refine") = py::none(), py::arg("anytime_ms") = 0.0, py::arg("highways") = py::none(),
        "the paper's interleaved plan/execute loop (lacam: full horizon), every step validated; returns a dict; "
        "iter_refine: refinement by iterative refinement instead of LNS (rtlacam-bench --iter-refine; None: on for "
        "lacam with anytime_ms, else off); anytime_ms: lacam with refine keeps refining (LaCAM*) until this much "
        "planning time, then executes (rtlacam-bench --anytime-ms); highways: PIBT's penalty for a move against a "
        "1-wide corridor's grain (rtlacam-bench --highways; None: 1 for RT-LaCAM*, else 0)");

  py::class_<Validator>(m, "Validator", "vertex/swap conflicts, adjacency; standard sum of costs and sum of loss")
      .def(py::init([](const Graph& g, const Config& starts, const Config& goals) {
             // step() indexes its vertex tables with the current configuration unchecked.
             check_config(g, starts, -1, "starts");
             check_config(g, goals, static_cast<int>(starts.size()), "goals");
             return std::make_unique<Validator>(g, starts, goals);
           }),
           py::arg("graph"), py::arg("starts"), py::arg("goals"), py::keep_alive<1, 2>())
      .def("step", &Validator::step, py::arg("next"), "checks current -> next and advances; False on a violation")
      .def("set_goals",
           [](Validator& v, const Config& goals) {
             check_config(v.graph(), goals, static_cast<int>(v.current().size()), "goals");
             v.set_goals(goals);
           },
           py::arg("goals"))
      .def_property_readonly("ok", &Validator::ok)
      .def_property_readonly("error", &Validator::error)
      .def_property_readonly("current", &Validator::current)
      .def_property_readonly("steps", &Validator::steps)
      .def_property_readonly("sum_of_costs", &Validator::sum_of_costs)
      .def_property_readonly("sum_of_loss", &Validator::sum_of_loss);
  m.def("validate_plan",
        [](const Graph& g, const Config& starts, const Config& goals, const std::vector<Config>& plan, bool require_goals) {
          check_config(g, starts, -1, "starts");  // a plan starting off the graph passed as valid
          check_config(g, goals, static_cast<int>(starts.size()), "goals");
          return validate_plan(g, starts, goals, plan, require_goals);
        },
        py::arg("graph"), py::arg("starts"), py::arg("goals"), py::arg("plan"),
        py::arg("require_goals") = true, "'' if the plan is valid, else the first violation");

  m.def("lifelong", &lifelong, py::arg("problem"), py::arg("solver") = "rtlacam", py::arg("steps") = -1,
        py::arg("budget_ms") = 100.0, py::arg("budget_expansions") = 0, py::arg("mode") = "",
        py::arg("assigner") = "greedy", py::arg("seed") = 0, py::arg("agents") = 0, py::arg("reassign") = false,
        py::arg("policy") = "", py::arg("battery") = py::none(), py::arg("chargers") = std::vector<Vertex>{},
        py::arg("pool_size") = 0, py::arg("k_nearest") = 32, py::arg("queues") = py::none(),
        py::arg("urgency") = py::none(), py::arg("parking") = py::none(), py::arg("action_model") = py::none(),
        py::arg("rotation") = py::none(), py::arg("highways") = 0,
        "a lifelong run on a League of Robot Runners problem JSON; returns rtlacam-lifelong's log (a dict). "
        "action_model: 'grid4' | 'rotation' (LoRR's headings, a step per quarter turn); default 'rotation' for the "
        "rotation solvers (pibt-rot, epibt, wppl: they need it), else 'grid4'. rotation: rotation solvers only, a dict "
        "of the SUMO YAML's planner.rotation keys (back_last, guidance: 'none' | 'arrows', guidance_costs: [along, "
        "against, turn], traffic_flow, depth, lns_rounds, revisit, priority: 'distance' | 'age', pocket_exit, "
        "leavers_first, window, neighbourhood; each only with the solver that reads it); unset keys take "
        "rtlacam-lifelong's defaults (arrows guidance for pibt-rot and epibt, none for wppl; traffic flow for epibt; "
        "priority 'distance'). highways: rtlacam / naive, rtlacam-lifelong --highways (PIBT ranks a move against a "
        "1-wide aisle's grain as 1 + highways; default 0, off). "
        "The task layer takes the SUMO controller's YAML options (tasks.*, fleet.battery): mode (tasks.assignment: "
        "roundrobin | pool; default the problem's), assigner, pool_size (0: the problem's), k_nearest, reassign; "
        "queues: a dict of tasks.queues' keys (capacity, length, admission, fifo, in_line (default True with epibt), clear_after, jam_after, one_way, leavers_first); urgency: a dict of tasks.urgency's "
        "(stalls: True | False | 'auto', battery, swap_after, head_after, load_cost, pocket_cost, escalate_after; default all off, as rtlacam-lifelong); parking: parking cell ids; "
        "battery: a dict of fleet.battery's keys (capacity_wh, initial, per_m_wh, per_turn_wh, threshold, critical, "
        "reserve_margin, rematch, task_check, target, charge_w, charging) on `chargers` (cell ids), as "
        "rtlacam-lifelong --battery-* --chargers");
}
