#include "controller/config.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "planner/rotation_settings.hpp"
#include "planner/solver.hpp"
#include "tasks/station_queues.hpp"

namespace controller {
namespace {

namespace fs = std::filesystem;

// Walks the YAML tree with the key path of every node, so each error names it.
class Reader {
 public:
  Reader(std::string file, std::string base) : file_(std::move(file)), base_(std::move(base)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const
  {
    throw ConfigError(file_ + ": " + one_line((key.empty() ? "" : key + ": ") + what));
  }
  // Control characters echoed from the YAML (a key or scalar "a\nb", yaml-cpp's "unknown
  // escape character: " + the character) are written as escapes: the message stays one line.
  static std::string one_line(const std::string& s)
  {
    std::string r;
    for (const unsigned char c : s) {
      if (c == '\n') r += "\\n";
      else if (c == '\r') r += "\\r";
      else if (c == '\t') r += "\\t";
      else if (c < 0x20 || c == 0x7f) {
        char hex[5];
        std::snprintf(hex, sizeof hex, "\\x%02x", c);
        r += hex;
      } else {
        r += static_cast<char>(c);
      }
    }
    return r;
  }

  // A mapping with only the given keys (a missing section is an empty mapping).
  void keys(const YAML::Node& n, const std::string& key, const std::set<std::string>& allowed) const
  {
    if (!n || n.IsNull()) return;
    if (!n.IsMap()) fail(key, "expected a mapping");
    for (const auto& kv : n) {
      // A complex key ("? [a]: 1") is no scalar: as<std::string>() threw yaml-cpp's bare
      // "bad conversion", naming neither the file nor the key path.
      if (!kv.first.IsScalar()) fail(key, "expected plain key names, got a list or mapping as a key");
      const std::string k = kv.first.as<std::string>();
      if (!allowed.count(k)) {
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(join(key, k), "unknown key (expected one of: " + list + ")");
      }
    }
  }

  template <class T>
  void get(const YAML::Node& parent, const std::string& key, const char* k, T& out, const char* type) const
  {
    if (!parent || !parent.IsMap() || !parent[k]) return;
    const YAML::Node n = parent[k];
    if (!n.IsScalar()) fail(join(key, k), std::string("expected ") + type);
    try {
      out = n.as<T>();
    } catch (const YAML::Exception&) {
      fail(join(key, k), std::string("expected ") + type + ", got '" + n.Scalar() + "'");
    }
  }
  void number(const YAML::Node& p, const std::string& key, const char* k, double& out, double lo, bool lo_open = false) const
  {
    get(p, key, k, out, "a number");
    if (!std::isfinite(out) || out < lo || (lo_open && out == lo))
      fail(join(key, k), "must be " + std::string(lo_open ? "> " : ">= ") + fmt(lo) + ", got " + fmt(out));
  }
  void flag(const YAML::Node& p, const std::string& key, const char* k, bool& out) const { get(p, key, k, out, "true or false"); }
  void text(const YAML::Node& p, const std::string& key, const char* k, std::string& out) const { get(p, key, k, out, "a string"); }
  void choice(const YAML::Node& p, const std::string& key, const char* k, std::string& out,
              const std::set<std::string>& allowed) const
  {
    text(p, key, k, out);
    if (!allowed.count(out)) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : "|") + a;
      fail(join(key, k), "'" + out + "' is not one of " + list);
    }
  }
  // A file that must exist; relative to the YAML file.
  void file(const YAML::Node& p, const std::string& key, const char* k, std::string& out, bool required) const
  {
    if (!p || !p.IsMap() || !p[k]) {
      if (required) fail(join(key, k), "missing (required)");
      return;
    }
    text(p, key, k, out);
    fs::path f(out);
    if (f.is_relative()) f = fs::path(base_) / f;
    f = f.lexically_normal();
    // The error_code overload: a name longer than NAME_MAX threw filesystem_error.
    std::error_code ec;
    if (!fs::is_regular_file(f, ec))
      fail(join(key, k), "file '" + f.string() + "' not found" + (ec ? " (" + ec.message() + ")" : std::string()));
    out = f.string();
  }
  // One cell: a vertex id, a station / junction id, or {lane: L, pos: P}.
  CellRef cell(const YAML::Node& n, const std::string& key) const
  {
    CellRef c;
    c.key = key;
    if (n.IsMap()) {
      keys(n, key, {"lane", "pos"});
      if (!n["lane"]) fail(join(key, "lane"), "missing (a lane position needs lane and pos)");
      if (!n["pos"]) fail(join(key, "pos"), "missing (a lane position needs lane and pos)");
      text(n, key, "lane", c.lane);
      number(n, key, "pos", c.pos, 0);
      return c;
    }
    if (!n.IsScalar()) fail(key, "expected a cell id, a station/junction id or {lane: L, pos: P}");
    int v = 0;
    if (YAML::convert<int>::decode(n, v)) c.vertex = v;
    else c.name = n.Scalar();
    return c;
  }
  // A list of cells.
  void cell_list(const YAML::Node& n, const std::string& key, std::vector<CellRef>& out) const
  {
    if (!n.IsSequence()) fail(key, "expected a list of cells");
    for (size_t i = 0; i < n.size(); ++i) out.push_back(cell(n[i], key + "[" + std::to_string(i) + "]"));
  }
  // `random` or a list of cells (vertex ids, station / junction ids, lane positions).
  void cells(const YAML::Node& p, const std::string& key, const char* k, bool& random, std::vector<CellRef>& out) const
  {
    if (!p || !p.IsMap() || !p[k]) return;
    const YAML::Node n = p[k];
    const std::string kk = join(key, k);
    if (n.IsScalar()) {
      if (n.Scalar() != "random") fail(kk, "expected 'random' or a list of cells, got '" + n.Scalar() + "'");
      random = true;
      return;
    }
    if (!n.IsSequence()) fail(kk, "expected 'random' or a list of cells");
    random = false;
    cell_list(n, kk, out);
  }
  // An integer in [lo, hi].
  void integer(const YAML::Node& p, const std::string& key, const char* k, int& out, int lo, int hi) const
  {
    get(p, key, k, out, "an integer");
    if (out < lo || out > hi)
      fail(join(key, k), "must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + std::to_string(out));
  }

  static std::string join(const std::string& a, const std::string& b) { return a.empty() ? b : a + "." + b; }
  static std::string fmt(double x)
  {
    std::ostringstream s;
    s << x;
    return s.str();
  }

 private:
  std::string file_, base_;
};

}  // namespace

// What to use instead of a SUMO option the controller sets (sumo_options.cpp), or null.
static const char* controlled_sumo_option(const std::string& opt)
{
  static const std::pair<const char*, const char*> kControlled[] = {
      {"-n", "use sumo.net"},
      {"--net-file", "use sumo.net"},
      {"-a", "use sumo.additional"},
      {"--additional-files", "use sumo.additional"},
      {"-c", "the controller builds the SUMO options from this YAML"},
      {"--configuration-file", "the controller builds the SUMO options from this YAML"},
      {"--step-length", "use sumo.step_length"},
      {"-b", "the run starts at 0"},
      {"--begin", "the run starts at 0"},
      {"-e", "use run.max_ticks"},
      {"--end", "use run.max_ticks"},
      {"--time-to-teleport", "AGVs must never be teleported (it stays -1)"},
      {"--collision.action", "collisions are reported, never resolved by SUMO (it stays warn)"},
      {"--collision.mingap-factor", "collisions are physical overlaps (it stays 0)"},
      {"--remote-port", "use run.port"},
      {"--fcd-output", "use sumo.outputs.fcd (written to output.dir)"},
      {"--tripinfo-output", "use sumo.outputs.tripinfo (written to output.dir)"},
      {"--summary-output", "use sumo.outputs.summary (written to output.dir)"},
      {"--collision-output", "use sumo.outputs.collision (written to output.dir)"},
  };
  for (const auto& [name, use] : kControlled)
    if (opt == name) return use;
  return nullptr;
}

// yaml-cpp keeps both entries of a repeated key and lookups find the first, so a typo'd
// second "tick_s:" would be ignored without a word: every mapping is checked up front.
// `seen`: the maps and sequences walked so far. An alias names a node already walked: once is
// enough -- a node aliasing itself (`a: &a {b: *a}`) recursed until the stack overflowed, and
// ten levels of ten aliases walked 10^10 nodes.
static void check_duplicate_keys(const Reader& r, const YAML::Node& n, const std::string& key, std::vector<YAML::Node>& seen_nodes)
{
  if (!n.IsSequence() && !n.IsMap()) return;
  for (const YAML::Node& s : seen_nodes)
    if (s.is(n)) return;
  seen_nodes.push_back(n);
  if (n.IsSequence()) {
    for (size_t i = 0; i < n.size(); ++i) check_duplicate_keys(r, n[i], key + "[" + std::to_string(i) + "]", seen_nodes);
    return;
  }
  std::map<std::string, int> seen;  // key -> line (1-based)
  for (const auto& kv : n) {
    if (!kv.first.IsScalar()) continue;  // Reader::keys names complex keys
    const std::string k = kv.first.Scalar();
    const std::string path = key.empty() ? k : key + "." + k;
    const auto [it, fresh] = seen.emplace(k, kv.first.Mark().line + 1);
    if (!fresh)
      r.fail(path, "duplicate key (line " + std::to_string(kv.first.Mark().line + 1) + "; first on line " +
                       std::to_string(it->second) + ")");
    check_duplicate_keys(r, kv.second, path, seen_nodes);
  }
}

// planner.rotation: only with a rotation solver, and each key only with the solver that reads it.
static void read_rotation(const Reader& r, const YAML::Node& p, planner::Solver kind, RotationSection& out)
{
  if (!p || !p.IsMap() || !p["rotation"]) return;
  const YAML::Node n = p["rotation"];
  const std::string key = "planner.rotation";
  if (!planner::plans_rotation(kind))
    r.fail(key, "only with a rotation solver (pibt-rot | epibt | wppl), not " + std::string(planner::to_string(kind)));
  // The keys and which solver reads which: planner/rotation_settings.hpp (Python's rotation=
  // dict has the same rules and messages).
  const std::vector<std::string>& names = planner::rotation_keys();
  r.keys(n, key, std::set<std::string>(names.begin(), names.end()));
  for (const std::string& k : names)
    if (n[k])
      if (const std::string why = planner::rotation_key_misuse(kind, k); !why.empty()) r.fail(key + "." + k, why);
  r.flag(n, key, "back_last", out.back_last);
  r.choice(n, key, "guidance", out.guidance, {"none", "arrows"});
  if (n["guidance_costs"]) {
    const YAML::Node c = n["guidance_costs"];
    if (out.guidance != "arrows") r.fail(key + ".guidance_costs", "only with guidance: arrows");
    if (!c.IsSequence() || c.size() != 3) r.fail(key + ".guidance_costs", "expected [along, against, turn]");
    for (size_t i = 0; i < 3; ++i) {
      int v = 0;
      if (!c[i].IsScalar() || !YAML::convert<int>::decode(c[i], v) || v < 1 || v > planner::Guidance::kMaxCost)
        r.fail(key + ".guidance_costs[" + std::to_string(i) + "]",
               "expected an integer in 1.." + std::to_string(planner::Guidance::kMaxCost));
      out.guidance_costs[i] = v;
    }
  }
  r.flag(n, key, "traffic_flow", out.traffic_flow);
  r.get(n, key, "depth", out.depth, "an integer");
  r.get(n, key, "lns_rounds", out.lns_rounds, "an integer");
  r.get(n, key, "revisit", out.revisit, "an integer");
  r.choice(n, key, "priority", out.priority, {"distance", "age"});
  r.flag(n, key, "pocket_exit", out.pocket_exit);
  r.flag(n, key, "leavers_first", out.leavers_first);
  r.get(n, key, "window", out.window, "an integer");
  r.get(n, key, "neighbourhood", out.neighbourhood, "an integer");
  // The ranges are the planners' (planner::check: "depth: must be in 3..5, got 7").
  if (const std::string e = planner::check(out); !e.empty()) {
    const size_t colon = e.find(": ");
    r.fail(key + "." + e.substr(0, colon), e.substr(colon + 2));
  }
}

bool PlannerSection::rotation_solver() const { return planner::plans_rotation(planner::parse_solver(solver)); }

void check_solver(const Config& c)
{
  auto fail = [&](const std::string& key, const std::string& what) { throw ConfigError(c.path + ": " + key + ": " + what); };
  const planner::Solver kind = planner::parse_solver(c.planner.solver);
  if (planner::needs_policy(kind) && c.planner.policy.empty()) fail("planner.solver", "cspibt needs planner.policy (a weights file)");
  if (c.fleet.turn_in_place && c.run.executor == "lockstep")
    fail("fleet.turn_s", "with a cell solver only under run.executor adg | adg-follow (the Driver turns the AGVs)");
  if (!planner::plans_rotation(kind)) return;
  if (!c.planner.policy.empty())
    fail("planner.policy", "orders a cell solver's moves; " + c.planner.solver + " plans rotation actions");
  // The AGVs turn on their cells, animated in SUMO step by step (lockstep: the planned turn
  // actions; adg, adg-follow: the Driver turns each AGV toward its next move), a turn a whole
  // number of SUMO steps.
  const double turn_steps = c.fleet.turn_s / c.sumo.step_length;
  if (std::fabs(turn_steps - std::round(turn_steps)) > 1e-9)
    fail("fleet.turn_s", "must be a whole multiple of sumo.step_length (" + Reader::fmt(c.sumo.step_length) + ")");
  if (c.fleet.turn_s > 3600) fail("fleet.turn_s", "must be <= 3600 s, got " + Reader::fmt(c.fleet.turn_s));
}

int Config::steps_per_tick() const { return static_cast<int>(std::lround(run.tick_s / sumo.step_length)); }

Config parse_config(const std::string& yaml, const std::string& name, const std::string& base_dir)
{
  Reader r(name, base_dir);
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    r.fail("", "not valid YAML: line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  if (!root.IsMap()) r.fail("", "expected a mapping with sections sumo, grid, fleet, planner, tasks, run, output");
  std::vector<YAML::Node> walked;
  check_duplicate_keys(r, root, "", walked);
  r.keys(root, "", {"sumo", "grid", "fleet", "planner", "tasks", "run", "delays", "output", "rules"});

  Config c;
  c.path = name;

  const YAML::Node s = root["sumo"];
  if (!s) r.fail("sumo", "missing (required: at least sumo.net)");
  r.keys(s, "sumo", {"net", "additional", "step_length", "extra_args", "outputs"});
  r.file(s, "sumo", "net", c.sumo.net, true);
  r.file(s, "sumo", "additional", c.sumo.additional, false);
  r.number(s, "sumo", "step_length", c.sumo.step_length, 0, true);
  if (s["extra_args"]) {
    const YAML::Node a = s["extra_args"];
    if (!a.IsSequence()) r.fail("sumo.extra_args", "expected a list of strings");
    for (size_t i = 0; i < a.size(); ++i) {
      if (!a[i].IsScalar()) r.fail("sumo.extra_args[" + std::to_string(i) + "]", "expected a string");
      c.sumo.extra_args.push_back(a[i].Scalar());
      // Options the controller sets itself: SUMO takes the last occurrence, so these would
      // silently change the run (or not apply, like --end) -- refused with the key to use.
      const std::string opt = c.sumo.extra_args.back().substr(0, c.sumo.extra_args.back().find('='));
      if (const char* use = controlled_sumo_option(opt))
        r.fail("sumo.extra_args[" + std::to_string(i) + "]", "'" + opt + "' is set by the controller: " + use);
    }
  }
  const YAML::Node o = s["outputs"];
  r.keys(o, "sumo.outputs", {"fcd", "tripinfo", "summary", "collision"});
  r.flag(o, "sumo.outputs", "fcd", c.sumo.outputs.fcd);
  r.flag(o, "sumo.outputs", "tripinfo", c.sumo.outputs.tripinfo);
  r.flag(o, "sumo.outputs", "summary", c.sumo.outputs.summary);
  r.flag(o, "sumo.outputs", "collision", c.sumo.outputs.collision);

  const YAML::Node g = root["grid"];
  r.keys(g, "grid", {"cell_length", "tolerance", "snap", "drop_one_way"});
  r.number(g, "grid", "cell_length", c.grid.cell_length, 0, true);
  r.number(g, "grid", "tolerance", c.grid.tolerance, 0);
  r.flag(g, "grid", "snap", c.grid.snap);
  r.flag(g, "grid", "drop_one_way", c.grid.drop_one_way);

  const YAML::Node f = root["fleet"];
  if (!f) r.fail("fleet", "missing (required: at least fleet.count)");
  r.keys(f, "fleet", {"count", "seed", "starts", "vtype", "turn_s", "battery"});
  r.get(f, "fleet", "seed", c.fleet.seed, "a non-negative integer");
  r.cells(f, "fleet", "starts", c.fleet.random_starts, c.fleet.starts);
  if (f["count"]) {
    r.get(f, "fleet", "count", c.fleet.count, "an integer");
    if (c.fleet.count < 1) r.fail("fleet.count", "must be >= 1, got " + std::to_string(c.fleet.count));
    if (!c.fleet.random_starts && static_cast<int>(c.fleet.starts.size()) != c.fleet.count)
      r.fail("fleet.starts", "lists " + std::to_string(c.fleet.starts.size()) + " cells but fleet.count is " +
                                 std::to_string(c.fleet.count));
  } else if (!c.fleet.random_starts) {
    c.fleet.count = static_cast<int>(c.fleet.starts.size());
  } else {
    r.fail("fleet.count", "missing (required with random starts)");
  }
  if (c.fleet.count < 1) r.fail("fleet.starts", "must list at least one cell");
  const YAML::Node v = f["vtype"];
  r.keys(v, "fleet.vtype", {"length", "width", "min_gap", "accel", "decel", "max_speed"});
  r.number(v, "fleet.vtype", "length", c.fleet.vtype.length, 0, true);
  r.number(v, "fleet.vtype", "width", c.fleet.vtype.width, 0, true);
  r.number(v, "fleet.vtype", "min_gap", c.fleet.vtype.min_gap, 0);
  r.number(v, "fleet.vtype", "accel", c.fleet.vtype.accel, 0, true);
  r.number(v, "fleet.vtype", "decel", c.fleet.vtype.decel, 0, true);
  r.number(v, "fleet.vtype", "max_speed", c.fleet.vtype.max_speed, 0, true);
  c.fleet.vtype.physics_given = v && v.IsMap() && (v["accel"] || v["decel"] || v["max_speed"]);
  r.number(f, "fleet", "turn_s", c.fleet.turn_s, 0, true);
  if (const YAML::Node b = f["battery"]) {
    FleetSection::Battery& x = c.fleet.battery;
    if (!b.IsMap()) r.fail("fleet.battery", "expected a mapping {capacity_wh, per_m_wh, per_turn_wh, threshold, target, ...}");
    r.keys(b, "fleet.battery", {"capacity_wh", "initial", "per_m_wh", "per_turn_wh", "threshold", "critical", "target", "charge_w",
                                "charging", "sample_ticks", "reserve_margin", "rematch", "task_check"});
    x.on = true;
    r.number(b, "fleet.battery", "capacity_wh", x.capacity_wh, 0, true);
    r.number(b, "fleet.battery", "per_m_wh", x.per_m_wh, 0);
    r.number(b, "fleet.battery", "per_turn_wh", x.per_turn_wh, 0);
    if (b["charge_w"]) r.number(b, "fleet.battery", "charge_w", x.charge_w, 0, true);
    r.number(b, "fleet.battery", "reserve_margin", x.reserve_margin, 0);
    r.flag(b, "fleet.battery", "rematch", x.rematch);
    r.flag(b, "fleet.battery", "task_check", x.task_check);
    r.flag(b, "fleet.battery", "charging", x.charging);
    r.integer(b, "fleet.battery", "sample_ticks", x.sample_ticks, 1, 1000000);
    for (auto [k, v] : {std::pair<const char*, double*>{"initial", &x.initial}, {"threshold", &x.threshold}, {"target", &x.target}}) {
      r.number(b, "fleet.battery", k, *v, 0, true);
      if (*v > 1) r.fail(std::string("fleet.battery.") + k, "is a fraction of capacity_wh: must be in (0, 1], got " + Reader::fmt(*v));
    }
    if (x.threshold >= x.target)
      r.fail("fleet.battery.threshold", "must be < target (" + Reader::fmt(x.target) + "), got " + Reader::fmt(x.threshold));
    if (b["critical"]) {
      r.number(b, "fleet.battery", "critical", x.critical, 0);
      if (x.critical >= x.threshold)
        r.fail("fleet.battery.critical", "must be < threshold (" + Reader::fmt(x.threshold) + "), got " + Reader::fmt(x.critical));
    } else {
      x.critical = std::min(x.critical, x.threshold / 2);  // the default stays below a low threshold
    }
  }
  if (c.fleet.vtype.length + c.fleet.vtype.min_gap > c.grid.cell_length + 1e-9)
    r.fail("fleet.vtype", "length + min_gap (" + Reader::fmt(c.fleet.vtype.length + c.fleet.vtype.min_gap) +
                              ") exceeds grid.cell_length (" + Reader::fmt(c.grid.cell_length) +
                              "): AGVs on adjacent cells would overlap");

  const YAML::Node p = root["planner"];
  r.keys(p, "planner", {"solver", "budget_ms", "expansions", "seed", "startup_ticks", "swap", "policy", "keep_priorities", "refine",
                        "dive", "lane_costs", "prefetch", "rotation", "stop_cost", "lns_moves", "free_first", "highways"});
  // Every real-time solver; lacam plans once, offline, and cannot follow SUMO.
  const std::vector<std::string> solvers = planner::solver_list(/*realtime_only=*/true);
  r.choice(p, "planner", "solver", c.planner.solver, {solvers.begin(), solvers.end()});
  r.file(p, "planner", "policy", c.planner.policy, false);
  const planner::Solver kind = planner::parse_solver(c.planner.solver);
  // Arrow guidance by default for every rotation solver: on SUMO warehouses it keeps opposite
  // flows apart in one-cell aisles (pibt-rot, large warehouse with queues, grid twin: 0.327 vs
  // 0.127 errands/step; small in SUMO: 0.101 vs 0.084). wppl since session 37: unguided it
  // decays at 1000 AGVs in SUMO (0.165 errands/tick, last/first 0.71; with arrows 0.581, 0.99)
  // and on the large twin (0.191 vs 0.282). rtlacam-lifelong keeps none for wppl (LoRR maps).
  // docs/twin_bench.md.
  if (planner::plans_rotation(kind)) c.planner.rotation.guidance = "arrows";
  // Station queues in line by default for epibt (tasks.queues.in_line; QueueOptions::in_line):
  // AGVs reach a queue lane in another order than they asked, and in a one-wide lane nobody
  // passes, so in request order the admitted AGV (or queue cell 0's) stands behind queued AGVs
  // on their cells. PIBT-style solvers push the line out and back; epibt cannot (an off-goal
  // robot has no wait, an operation that meets two robots is no candidate): at 1000 AGVs in
  // SUMO its stations starved behind such lines (pickup26: the admitted AGV behind five queued
  // ones for 1000+ ticks, the station free) and it collapsed (huge, 2500 ticks, p = 0: 0.245
  // errands/tick, last/first 500 0.58; in line 0.546, 1.00). Session 38, docs/twin_bench.md.
  // The other solvers keep request order (large_warehouse_queues' pibt-rot rows were mixed, s36).
  c.tasks.queue_in_line = tasks::in_line_by_default(planner::to_string(kind));
  read_rotation(r, p, kind, c.planner.rotation);
  r.number(p, "planner", "budget_ms", c.planner.budget_ms, 0);
  r.get(p, "planner", "expansions", c.planner.expansions, "a non-negative integer");
  r.get(p, "planner", "seed", c.planner.seed, "a non-negative integer");
  r.integer(p, "planner", "startup_ticks", c.planner.startup_ticks, 0, 1000);
  r.flag(p, "planner", "swap", c.planner.swap);
  r.flag(p, "planner", "keep_priorities", c.planner.keep_priorities);
  r.flag(p, "planner", "refine", c.planner.refine);
  r.flag(p, "planner", "dive", c.planner.dive);
  r.get(p, "planner", "stop_cost", c.planner.stop_cost, "a non-negative integer");
  r.flag(p, "planner", "lns_moves", c.planner.lns_moves);
  r.flag(p, "planner", "free_first", c.planner.free_first);
  r.integer(p, "planner", "highways", c.planner.highways, 0, 200);
  if (c.planner.stop_cost < 0) r.fail("planner.stop_cost", "must be >= 0, got " + std::to_string(c.planner.stop_cost));
  r.flag(p, "planner", "lane_costs", c.planner.lane_costs);
  r.flag(p, "planner", "prefetch", c.planner.prefetch);
  if (c.planner.budget_ms == 0 && c.planner.expansions == 0)
    r.fail("planner.budget_ms", "0 needs planner.expansions > 0 (some limit per SUMO step)");

  const YAML::Node t = root["tasks"];
  r.keys(t, "tasks", {"mode", "goals", "seed", "pickups", "drops", "random", "list", "assignment", "assigner",
                      "pool_size", "k_nearest", "reassign", "queues", "parking", "urgency", "log"});
  r.choice(t, "tasks", "mode", c.tasks.mode, {"one_shot", "lifelong"});
  r.get(t, "tasks", "seed", c.tasks.seed, "a non-negative integer");
  if (c.fleet.battery.on && !c.tasks.lifelong()) r.fail("fleet.battery", "only with tasks.mode: lifelong (charging errands are lifelong work)");
  if (!c.tasks.lifelong()) {
    for (const char* k : {"pickups", "drops", "random", "list", "assignment", "assigner", "pool_size", "k_nearest", "reassign",
                          "queues", "parking", "urgency", "log"})
      if (t && t.IsMap() && t[k]) r.fail(std::string("tasks.") + k, "only with tasks.mode: lifelong");
    r.cells(t, "tasks", "goals", c.tasks.random_goals, c.tasks.goals);
    if (!c.tasks.random_goals && static_cast<int>(c.tasks.goals.size()) != c.fleet.count)
      r.fail("tasks.goals", "lists " + std::to_string(c.tasks.goals.size()) + " cells but the fleet has " +
                                std::to_string(c.fleet.count) + " AGVs");
  } else {
    if (t["goals"]) r.fail("tasks.goals", "only with tasks.mode: one_shot (lifelong goals come from the tasks)");
    if (t["pickups"]) r.cell_list(t["pickups"], "tasks.pickups", c.tasks.pickups);
    if (t["drops"]) r.cell_list(t["drops"], "tasks.drops", c.tasks.drops);
    if (t["pickups"] && c.tasks.pickups.empty()) r.fail("tasks.pickups", "must list at least one cell");
    if (t["drops"] && c.tasks.drops.empty()) r.fail("tasks.drops", "must list at least one cell");
    if (t["random"] && t["list"]) r.fail("tasks.list", "give either tasks.random or tasks.list, not both");
    if (t["list"]) {
      const YAML::Node l = t["list"];
      c.tasks.random_tasks = false;
      if (!l.IsSequence() || l.size() == 0) r.fail("tasks.list", "expected a non-empty list of tasks (each a list of errand cells)");
      for (size_t i = 0; i < l.size(); ++i) {
        const std::string key = "tasks.list[" + std::to_string(i) + "]";
        std::vector<CellRef> task;
        r.cell_list(l[i], key, task);
        if (task.empty()) r.fail(key, "a task needs at least one errand cell");
        c.tasks.list.push_back(std::move(task));
      }
    } else {
      const YAML::Node rn = t["random"];
      r.keys(rn, "tasks.random", {"count", "errands"});
      r.integer(rn, "tasks.random", "count", c.tasks.count, 1, 10000000);
      r.integer(rn, "tasks.random", "errands", c.tasks.errands, 1, 100);
    }
    r.choice(t, "tasks", "assignment", c.tasks.assignment, {"roundrobin", "pool"});
    if (c.tasks.assignment != "pool")
      for (const char* k : {"assigner", "pool_size", "k_nearest", "reassign"})
        if (t[k]) r.fail(std::string("tasks.") + k, "only with tasks.assignment: pool");
    r.choice(t, "tasks", "assigner", c.tasks.assigner, {"greedy", "hungarian"});
    r.integer(t, "tasks", "pool_size", c.tasks.pool_size, 0, 10000000);
    r.integer(t, "tasks", "k_nearest", c.tasks.k_nearest, 1, 1000000);
    r.flag(t, "tasks", "reassign", c.tasks.reassign);
    if (const YAML::Node u = t["urgency"]) {
      if (!u.IsMap())
        r.fail("tasks.urgency", "expected a mapping {stalls: true|false|auto, battery: true|false, swap_after: N, head_after: N, load_cost: N, pocket_cost: N, drop_hints: true|false, mouth_cost: N, sticky: true|false, escalate_after: N}");
      r.keys(u, "tasks.urgency", {"stalls", "battery", "swap_after", "head_after", "load_cost", "pocket_cost", "drop_hints", "mouth_cost", "sticky", "escalate_after"});
      r.integer(u, "tasks.urgency", "escalate_after", c.tasks.urgency_escalate_after, 0, 1000000000);
      r.integer(u, "tasks.urgency", "swap_after", c.tasks.urgency_swap_after, 0, 1000000000);
      r.integer(u, "tasks.urgency", "head_after", c.tasks.urgency_head_after, 0, 1000000000);
      r.integer(u, "tasks.urgency", "load_cost", c.tasks.urgency_load_cost, 0, 1000000);
      r.integer(u, "tasks.urgency", "pocket_cost", c.tasks.urgency_pocket_cost, 0, 1000000);
      r.flag(u, "tasks.urgency", "drop_hints", c.tasks.urgency_drop_hints);
      r.integer(u, "tasks.urgency", "mouth_cost", c.tasks.urgency_mouth_cost, 0, 254);
      r.flag(u, "tasks.urgency", "sticky", c.tasks.urgency_sticky);
      if (u["stalls"] && !(u["stalls"].IsScalar() && u["stalls"].Scalar() == "auto")) {
        bool on = false;
        r.get(u, "tasks.urgency", "stalls", on, "true, false or auto");
        c.tasks.urgency_stalls = on;
      }
      r.flag(u, "tasks.urgency", "battery", c.tasks.urgency_battery);
    }
    if (const YAML::Node q = t["queues"]) {
      if (!q.IsMap()) r.fail("tasks.queues", "expected a mapping {capacity: K, length: L, admission: A, fifo: B, clear_after: N, jam_after: N, one_way: B, in_line: B, leavers_first: B, idle_clear: B}");
      r.keys(q, "tasks.queues", {"capacity", "length", "admission", "fifo", "clear_after", "jam_after", "one_way", "in_line", "leavers_first", "idle_clear"});
      r.flag(q, "tasks.queues", "in_line", c.tasks.queue_in_line);
      r.flag(q, "tasks.queues", "leavers_first", c.tasks.queue_leavers_first);
      r.flag(q, "tasks.queues", "idle_clear", c.tasks.queue_idle_clear);
      r.integer(q, "tasks.queues", "clear_after", c.tasks.queue_clear_after, 0, 1000000000);
      r.integer(q, "tasks.queues", "jam_after", c.tasks.queue_jam_after, 0, 1000000000);
      r.flag(q, "tasks.queues", "one_way", c.tasks.queue_one_way);
      if (c.tasks.queue_leavers_first && c.tasks.queue_clear_after == 0)
        r.fail("tasks.queues.leavers_first", "needs clear_after > 0 (it acts while a station clears its pocket)");
      r.flag(q, "tasks.queues", "fifo", c.tasks.queue_fifo);
      r.integer(q, "tasks.queues", "capacity", c.tasks.queue_capacity, 0, 1000000);
      r.integer(q, "tasks.queues", "length", c.tasks.queue_length, 0, 1000000);
      r.integer(q, "tasks.queues", "admission", c.tasks.queue_admission, -1, 10000000);
      if (c.tasks.queue_admission > 0 && c.tasks.queue_admission < c.tasks.queue_capacity)
        r.fail("tasks.queues.admission", "must be >= capacity (" + std::to_string(c.tasks.queue_capacity) + "), 0 or -1, got " +
                                             std::to_string(c.tasks.queue_admission));
    }
    if (const YAML::Node pk = t["parking"]) {
      if (pk.IsSequence()) {
        r.cell_list(pk, "tasks.parking", c.tasks.parking_cells);
        if (c.tasks.parking_cells.empty()) r.fail("tasks.parking", "must list at least one cell (or be true / false)");
        c.tasks.parking = true;
      } else {
        r.get(t, "tasks", "parking", c.tasks.parking, "true (the parkingAreas of sumo.additional), false or a list of cells");
        c.tasks.parking_auto = c.tasks.parking;
      }
    }
    r.text(t, "tasks", "log", c.tasks.log);
    if (c.tasks.log.empty() || c.tasks.log.find('/') != std::string::npos)
      r.fail("tasks.log", "expected a file name (written in output.dir), got '" + c.tasks.log + "'");
  }

  const YAML::Node u = root["run"];
  r.keys(u, "run", {"tick_s", "max_ticks", "backend", "gui", "gui_delay_ms", "port", "order", "progress_s", "executor",
                    "window", "drain", "replan_on_stuck", "stuck_after_s", "stuck_learn", "relative_braking", "leader_decel", "same_step_starts", "switch_passages",
                    "chain_to_end", "gap_handover", "lane_speeds", "epoch_in_budget", "out_and_back",
                    "cut_loops", "out_and_back_rules", "plan_completions"});
  r.number(u, "run", "tick_s", c.run.tick_s, 0, true);
  r.get(u, "run", "max_ticks", c.run.max_ticks, "an integer");
  if (c.run.max_ticks < 1) r.fail("run.max_ticks", "must be >= 1");
  r.choice(u, "run", "backend", c.run.backend, {"libsumo", "traci"});
  r.flag(u, "run", "gui", c.run.gui);
  r.number(u, "run", "gui_delay_ms", c.run.gui_delay_ms, 0);
  r.get(u, "run", "port", c.run.port, "an integer");
  if (c.run.port < 0 || c.run.port > 65535) r.fail("run.port", "must be in 0..65535");
  if (c.run.port > 0 && !(u && u["backend"])) c.run.backend = "traci";  // the port is a TraCI one
  if (u && u["order"]) {
    r.integer(u, "run", "order", c.run.order, 1, 1000000);
    if (c.run.port == 0) r.fail("run.order", "only with run.port (a SUMO started with --num-clients, which this client joins)");
  }
  r.number(u, "run", "progress_s", c.run.progress_s, 0);
  r.choice(u, "run", "executor", c.run.executor, {"lockstep", "adg", "adg-follow"});
  r.integer(u, "run", "window", c.run.window, 1, 1000000);
  if (u && u["drain"]) r.integer(u, "run", "drain", c.run.drain, 1, c.run.window);
  r.flag(u, "run", "replan_on_stuck", c.run.replan_on_stuck);
  r.number(u, "run", "stuck_after_s", c.run.stuck_after_s, 0, true);
  r.flag(u, "run", "stuck_learn", c.run.stuck_learn);
  r.flag(u, "run", "relative_braking", c.run.relative_braking);
  r.number(u, "run", "leader_decel", c.run.leader_decel, 0);
  if (c.run.leader_decel > 0 && c.run.leader_decel < c.fleet.vtype.decel)
    r.fail("run.leader_decel", "must be >= fleet.vtype.decel (" + Reader::fmt(c.fleet.vtype.decel) + "): every AGV can brake that hard");
  r.flag(u, "run", "same_step_starts", c.run.same_step_starts);
  r.integer(u, "run", "switch_passages", c.run.switch_passages, 0, 1000);
  r.flag(u, "run", "chain_to_end", c.run.chain_to_end);
  r.flag(u, "run", "gap_handover", c.run.gap_handover);
  r.flag(u, "run", "plan_completions", c.run.plan_completions);
  r.integer(u, "run", "out_and_back", c.run.out_and_back, 0, 1000);
  r.flag(u, "run", "cut_loops", c.run.cut_loops);
  r.flag(u, "run", "out_and_back_rules", c.run.out_and_back_rules);
  r.flag(u, "run", "lane_speeds", c.run.lane_speeds);
  r.flag(u, "run", "epoch_in_budget", c.run.epoch_in_budget);
  // A stuck replan needs an ADG to cut the plan at (stuck_replan.hpp); lock-step has none.
  // With adg-follow a rotation group's members finish together (Driver::group_arrived), so the
  // cut plan is valid there too (the vertex conflicts measured before that fix are gone).
  if (c.run.executor == "lockstep" && u && u["replan_on_stuck"] && c.run.replan_on_stuck)
    r.fail("run.replan_on_stuck", "only with run.executor: adg or adg-follow");
  // A stuck replan rebuilds a cell planner around immobile AGVs (stuck_replan.hpp); the
  // rotation solvers have no immobile agents and the replan no headings: off for them.
  if (c.planner.rotation_solver() && c.run.replan_on_stuck && c.run.executor != "lockstep") {
    if (u && u["replan_on_stuck"])
      r.fail("run.replan_on_stuck", "only with a cell solver (rtlacam | naive | pibt | cspibt), not " + c.planner.solver);
    c.run.replan_on_stuck = false;
  }
  // Upper bounds: a tick of 1e300 s overflowed the steps per tick (a crash in lockstep, an
  // idle run under adg); an hour per MAPF step and 10000 SUMO steps per tick are far past
  // any warehouse.
  if (c.run.tick_s > 3600) r.fail("run.tick_s", "must be <= 3600 s, got " + Reader::fmt(c.run.tick_s));
  const double k = c.run.tick_s / c.sumo.step_length;
  if (std::fabs(k - std::round(k)) > 1e-9 || std::round(k) < 1)
    r.fail("run.tick_s", "must be a whole multiple of sumo.step_length (" + Reader::fmt(c.sumo.step_length) + ")");
  if (k > 10000)
    r.fail("run.tick_s", "at most 10000 SUMO steps per tick (run.tick_s / sumo.step_length = " + Reader::fmt(k) + ")");

  check_solver(c);
  if (!c.planner.rotation_solver() && f["turn_s"]) {
    if (c.run.executor == "lockstep")
      r.fail("fleet.turn_s", "only with a rotation solver (pibt-rot | epibt | wppl) or run.executor adg | adg-follow: " +
                                 c.planner.solver + "'s AGVs turn with their lanes in lockstep");
    // A cell solver under the physical executors: the Driver turns the AGVs on their cells.
    c.fleet.turn_in_place = true;
    const double turn_steps = c.fleet.turn_s / c.sumo.step_length;
    if (std::fabs(turn_steps - std::round(turn_steps)) > 1e-9)
      r.fail("fleet.turn_s", "must be a whole multiple of sumo.step_length (" + Reader::fmt(c.sumo.step_length) + ")");
    if (c.fleet.turn_s > 3600) r.fail("fleet.turn_s", "must be <= 3600 s, got " + Reader::fmt(c.fleet.turn_s));
  }

  // Delays: seconds -> ticks (rounded up), then executor::check for the ranges.
  const YAML::Node d = root["delays"];
  r.keys(d, "delays", {"kind", "p", "rate", "duration_s", "fraction", "seed", "slow", "stuck"});
  executor::DelaySpec& ds = c.delays.spec;
  auto ticks = [&](double sec) { return static_cast<long long>(std::ceil(sec / c.run.tick_s - 1e-9)); };
  r.choice(d, "delays", "kind", ds.kind, {"none", "bernoulli", "poisson"});
  r.get(d, "delays", "p", ds.p, "a number");
  r.get(d, "delays", "rate", ds.rate, "a number");
  r.number(d, "delays", "fraction", ds.fraction, 0, true);
  r.get(d, "delays", "seed", ds.seed, "a non-negative integer");
  if (d && d.IsMap() && d["duration_s"]) {
    const YAML::Node n = d["duration_s"];
    if (!n.IsSequence() || n.size() != 2) r.fail("delays.duration_s", "expected [min, max] seconds");
    double lo = 0, hi = 0;
    try {
      lo = n[0].as<double>();
      hi = n[1].as<double>();
    } catch (const YAML::Exception&) {
      r.fail("delays.duration_s", "expected [min, max] seconds");
    }
    if (!(lo > 0) || !(hi >= lo) || !std::isfinite(hi))
      r.fail("delays.duration_s", "needs 0 < min <= max, got [" + Reader::fmt(lo) + ", " + Reader::fmt(hi) + "]");
    ds.min_ticks = ticks(lo);
    ds.max_ticks = ticks(hi);
  }
  auto agent_list = [&](const char* k, auto&& each) {
    if (!d || !d.IsMap() || !d[k]) return;
    const YAML::Node l = d[k];
    const std::string key = std::string("delays.") + k;
    if (!l.IsSequence()) r.fail(key, "expected a list of mappings");
    for (size_t i = 0; i < l.size(); ++i) each(l[i], key + "[" + std::to_string(i) + "]");
  };
  agent_list("slow", [&](const YAML::Node& n, const std::string& key) {
    r.keys(n, key, {"agent", "factor"});
    executor::Slowdown sd;
    r.get(n, key, "agent", sd.agent, "an integer");
    r.get(n, key, "factor", sd.factor, "a number");
    ds.slow.push_back(sd);
  });
  agent_list("stuck", [&](const YAML::Node& n, const std::string& key) {
    r.keys(n, key, {"agent", "at_s", "for_s"});
    double at = 0, dur = 0;
    executor::Stuck st;
    r.get(n, key, "agent", st.agent, "an integer");
    r.number(n, key, "at_s", at, 0);
    r.number(n, key, "for_s", dur, 0, true);
    st.at = static_cast<long long>(std::floor(at / c.run.tick_s + 1e-9));
    st.ticks = ticks(dur);
    ds.stuck.push_back(st);
  });
  if (const std::string e = executor::check(ds, c.fleet.count); !e.empty()) {
    const size_t colon = e.find(": ");
    r.fail("delays." + e.substr(0, colon), e.substr(colon + 2));
  }

  const YAML::Node w = root["output"];
  r.keys(w, "output", {"dir", "plan", "plan_keep", "congestion", "queue_trace", "gui_snapshots"});
  r.text(w, "output", "dir", c.output.dir);
  r.flag(w, "output", "plan", c.output.plan);
  r.integer(w, "output", "plan_keep", c.output.plan_keep, 0, 1 << 30);
  r.flag(w, "output", "congestion", c.output.congestion);
  r.integer(w, "output", "queue_trace", c.output.queue_trace, 0, 1 << 30);
  if (w && w.IsMap() && w["gui_snapshots"]) {
    const YAML::Node l = w["gui_snapshots"];
    if (!l.IsSequence()) r.fail("output.gui_snapshots", "expected a list of simulated seconds");
    for (size_t i = 0; i < l.size(); ++i) {
      const std::string key = "output.gui_snapshots[" + std::to_string(i) + "]";
      double t = -1;
      // decode() leaves 0 behind on a failed parse: its result decides.
      if (!l[i].IsScalar() || !YAML::convert<double>::decode(l[i], t) || !(t >= 0) || !std::isfinite(t))
        r.fail(key, "expected simulated seconds >= 0");
      c.output.gui_snapshots.push_back(t);
    }
  }

  // Rules (rules.hpp): closures and one-at-a-time zones.
  const YAML::Node ru = root["rules"];
  r.keys(ru, "rules", {"sumo", "watch_lanes", "closures", "zones", "enforce_closures", "enforce_zones", "plan_zones", "reassign"});
  r.flag(ru, "rules", "sumo", c.rules.sumo);
  if (ru && ru.IsMap() && ru["watch_lanes"]) {
    bool w = false;
    r.flag(ru, "rules", "watch_lanes", w);
    c.rules.watch_lanes = w;
  }
  r.flag(ru, "rules", "enforce_closures", c.rules.enforce_closures);
  r.flag(ru, "rules", "enforce_zones", c.rules.enforce_zones);
  if (ru && ru.IsMap() && ru["plan_zones"] && !(ru["plan_zones"].IsScalar() && ru["plan_zones"].Scalar() == "auto")) {
    bool on = false;
    r.get(ru, "rules", "plan_zones", on, "true, false or auto");
    c.rules.plan_zones = on;
  }
  r.flag(ru, "rules", "reassign", c.rules.reassign);
  auto names = [&](const YAML::Node& n, const std::string& key, const char* k, std::vector<std::string>& out) {
    if (!n[k]) return;
    const YAML::Node l = n[k];
    const std::string kk = key + "." + k;
    if (!l.IsSequence()) r.fail(kk, "expected a list of ids");
    for (size_t i = 0; i < l.size(); ++i) {
      if (!l[i].IsScalar()) r.fail(kk + "[" + std::to_string(i) + "]", "expected an id");
      out.push_back(l[i].Scalar());
    }
  };
  auto rule_list = [&](const char* k, auto&& each) {
    if (!ru || !ru.IsMap() || !ru[k]) return;
    const YAML::Node l = ru[k];
    const std::string key = std::string("rules.") + k;
    if (!l.IsSequence()) r.fail(key, "expected a list of mappings");
    for (size_t i = 0; i < l.size(); ++i) {
      const std::string ki = key + "[" + std::to_string(i) + "]";
      if (!l[i].IsMap()) r.fail(ki, "expected a mapping");
      each(l[i], ki);
    }
  };
  rule_list("closures", [&](const YAML::Node& n, const std::string& key) {
    r.keys(n, key, {"lanes", "edges", "cells", "begin", "end"});
    RuleClosure cl;
    cl.key = key;
    names(n, key, "lanes", cl.lanes);
    names(n, key, "edges", cl.edges);
    if (n["cells"]) r.cell_list(n["cells"], key + ".cells", cl.cells);
    if (cl.lanes.empty() && cl.edges.empty() && cl.cells.empty())
      r.fail(key, "closes nothing (give lanes, edges or cells)");
    r.number(n, key, "begin", cl.begin, 0);
    if (n["end"]) {
      r.number(n, key, "end", cl.end, 0);
      if (cl.end < cl.begin)
        r.fail(key + ".end", "end " + Reader::fmt(cl.end) + " < begin " + Reader::fmt(cl.begin));
    }
    c.rules.closures.push_back(std::move(cl));
  });
  rule_list("zones", [&](const YAML::Node& n, const std::string& key) {
    r.keys(n, key, {"id", "lanes", "edges", "cells"});
    RuleZone z;
    z.key = key;
    z.id = key;
    r.text(n, key, "id", z.id);
    names(n, key, "lanes", z.lanes);
    names(n, key, "edges", z.edges);
    if (n["cells"]) r.cell_list(n["cells"], key + ".cells", z.cells);
    if (z.lanes.empty() && z.edges.empty() && z.cells.empty()) r.fail(key, "a zone with no cells (give lanes, edges or cells)");
    c.rules.zones.push_back(std::move(z));
  });
  return c;
}

Config load_config(const std::string& path)
{
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open the config file");
  // A folder read as "expected a mapping"; /dev/zero was read for ever.
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw ConfigError(path + ": is a directory, not a config file");
  if (!fs::is_regular_file(path, ec) && !fs::is_fifo(path, ec))
    throw ConfigError(path + ": not a regular file (a config is a YAML file)");
  std::stringstream ss;
  ss << in.rdbuf();
  fs::path base = fs::path(path).parent_path();
  return parse_config(ss.str(), path, base.empty() ? "." : base.string());
}

}  // namespace controller
