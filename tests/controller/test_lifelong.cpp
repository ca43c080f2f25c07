// Lifelong tasks in SUMO (tasks.mode: lifelong): the task layer of tasks/ driving the
// controller. Real SUMO 1.15 through libsumo; ctest runs each TEST in its own process.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <algorithm>
#include <set>

#include "controller/config.hpp"
#include "controller_test_util.hpp"
#include "controller/controller.hpp"
#include "controller/lifelong.hpp"
#include "planner/validator.hpp"
#include "tasks/station_queues.hpp"
#include "tasks/task_builder.hpp"
#include "temp_path.hpp"

using namespace controller;
namespace fs = std::filesystem;

namespace {

std::string temp_dir(const std::string& name) { return test::temp_dir("ll_" + name); }

Config lifelong_config(const std::string& name, long long ticks)
{
  Config c = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse_lifelong.yaml");
  c.output.dir = temp_dir(name);
  c.run.progress_s = 0;
  c.run.max_ticks = ticks;
  // Deterministic: a fixed number of expansions per SUMO step, no wall-clock cutoff.
  c.planner.budget_ms = 0;
  c.planner.expansions = 20;
  return c;
}

nlohmann::json read_json(const std::string& path)
{
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// A clean lifelong run: no violation, positions exact, the executed plan valid, every
// logged event an AGV standing on its errand cell at the end of that tick.
void expect_clean_lifelong_run(const Config& cfg, const Controller& c, const Metrics& m)
{
  EXPECT_EQ(m.error, "");
  EXPECT_FALSE(m.solved);
  EXPECT_EQ(m.mode, "lifelong");
  EXPECT_EQ(m.ticks, cfg.run.max_ticks);
  EXPECT_EQ(m.violations, 0);
  EXPECT_EQ(m.commands.resyncs, 0);
  EXPECT_LE(m.commands.max_error, 1e-6);
  EXPECT_EQ(m.commands.jumps, 0);
  const auto& plan = c.plan();
  ASSERT_EQ(static_cast<long long>(plan.size()), m.ticks + 1);
  EXPECT_EQ(planner::validate_plan(c.map().graph, plan.front(), plan.back(), plan, false), "");

  const nlohmann::json j = read_json(cfg.output.dir + "/" + cfg.tasks.log);
  for (const char* k : {"actionModel", "teamSize", "numTaskFinished", "numErrandFinished", "makespan", "taskThroughput",
                        "errandThroughput", "plannerTimes", "numPlannerErrors", "events", "mode", "assigner", "solver",
                        "budgetMs", "seed", "epochs"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["teamSize"], m.agents);
  EXPECT_EQ(j["makespan"], m.ticks);
  EXPECT_EQ(j["numPlannerErrors"], 0);
  EXPECT_EQ(j["numErrandFinished"], m.errands_finished);
  EXPECT_EQ(j["numTaskFinished"], m.tasks_finished);
  EXPECT_DOUBLE_EQ(j["taskThroughput"].get<double>(), static_cast<double>(m.tasks_finished) / m.ticks);
  EXPECT_EQ(j["mode"], cfg.tasks.assignment);
  for (const char* k : {"mean", "p50", "p99", "max"}) EXPECT_TRUE(j["plannerTimeStats"].contains(k)) << k;
  ASSERT_EQ(static_cast<long long>(j["events"].size()), m.errands_finished);

  // Every event: the AGV stands on the errand's cell at the end of tick t (plan[t]).
  const auto file = make_task_file(cfg, c.map());
  long last_t = 0;
  for (const auto& e : j["events"]) {
    const long t = e[0], task = e[2];
    const int agent = e[1], errand = e[3].get<int>() - 1;  // LoRR: errands done
    ASSERT_GE(t, 1);
    ASSERT_LE(t, m.ticks);
    EXPECT_GE(t, last_t);
    last_t = t;
    const auto& errands = file->tasks[static_cast<size_t>(task % file->size())];
    ASSERT_LT(errand, static_cast<int>(errands.size()));
    EXPECT_EQ(plan[t][agent], errands[errand]) << "t " << t << " agent " << agent << " task " << task;
  }
  const nlohmann::json mj = read_json(cfg.output.dir + "/metrics.json");
  EXPECT_EQ(mj["mode"], "lifelong");
  // The free-flow bound (tasks/free_flow.hpp), recomputed here with a BFS of our own: each
  // AGV alone from its start through its finished errands' cells, a move per tick (lockstep).
  if (cfg.run.executor == "lockstep" && m.errands_finished > 0) {
    const planner::Graph& g = c.map().graph;
    auto moves = [&](planner::Vertex from, planner::Vertex to) {
      std::vector<int> d(g.size(), -1);
      std::vector<planner::Vertex> q{from};
      d[from] = 0;
      for (size_t h = 0; h < q.size(); ++h)
        for (planner::Vertex u : g.neighbors(q[h]))
          if (d[u] < 0) d[u] = d[q[h]] + 1, q.push_back(u);
      return d[to];
    };
    planner::Config last = plan.front();
    double steps = 0;
    for (const auto& e : j["events"]) {
      const int agent = e[1];
      const planner::Vertex cell = plan[e[0].get<long>()][agent];
      steps += moves(last[agent], cell);
      last[agent] = cell;
    }
    ASSERT_GT(steps, 0);
    const double bound = static_cast<double>(m.agents) * static_cast<double>(m.errands_finished) / steps;
    EXPECT_NEAR(mj["lifelong"]["freeFlowBoundFinishedOnly"].get<double>(), bound, 1e-9);
    EXPECT_NEAR(j["freeFlowBoundFinishedOnly"].get<double>(), bound, 1e-9);
    EXPECT_LE(m.errand_throughput(), bound + 1e-9);  // nobody beats driving alone
  }
  // The bound itself also prices the errands open at the end (free_flow.hpp); both logs agree.
  if (m.errands_finished > 0) {
    const double bound = mj["lifelong"]["freeFlowBound"].get<double>();
    EXPECT_GT(bound, 0);
    EXPECT_NEAR(j["freeFlowBound"].get<double>(), bound, 1e-9);
    EXPECT_NEAR(mj["lifelong"]["errandThroughputOverFreeFlow"].get<double>(), m.errand_throughput() / bound, 1e-9);
  }
  EXPECT_EQ(mj["lifelong"]["numErrandFinished"], m.errands_finished);
  ctest_util::expect_no_sumo_collision(cfg.output.dir);
}

using ctest_util::config_error;

std::string run_error(const std::string& yaml)
{
  Config c = parse_config(yaml, "t.yaml", RTLACAM_CONFIGS);
  c.output.dir = temp_dir("cells");
  c.run.max_ticks = 1;
  try {
    Controller(c).run();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kNet = "sumo:\n  net: ../sumo_scenarios/small.net.xml\n";
const std::string kNetAdd = kNet + "  additional: ../sumo_scenarios/small.add.xml\n";

}  // namespace

TEST(ControllerLifelong, SmallWarehousePoolServesTasksExactly)
{
  Config cfg = lifelong_config("pool", 200);
  Controller c(cfg);
  const Metrics m = c.run();
  expect_clean_lifelong_run(cfg, c, m);
  EXPECT_GE(m.errands_finished, 15);  // measured 22 errands, 4 tasks (controller/README.md)
  EXPECT_GE(m.tasks_finished, 3);
  EXPECT_EQ(m.epochs, read_json(cfg.output.dir + "/lifelong.json")["epochs"].get<long long>());
}

TEST(ControllerLifelong, RoundRobinListedTasksWithSharedGoals)
{
  // Every AGV gets the same two-errand task (lane position, then a cell id): all goals
  // coincide, which the lifelong goal test must handle.
  Config cfg = lifelong_config("roundrobin", 120);
  Config y = parse_config(kNetAdd +
                              "fleet: {count: 6, seed: 4}\n"
                              "tasks:\n  mode: lifelong\n  assignment: roundrobin\n"
                              "  list: [[{lane: c1r0_pick1_0, pos: 1.75}, drop3], [pickup2, drop0]]\n",
                          "t.yaml", RTLACAM_CONFIGS);
  y.output = cfg.output;
  y.run.progress_s = 0;
  y.run.max_ticks = 120;
  y.planner = cfg.planner;
  Controller c(y);
  const Metrics m = c.run();
  expect_clean_lifelong_run(y, c, m);
  EXPECT_GE(m.errands_finished, 6);
  EXPECT_EQ(read_json(y.output.dir + "/lifelong.json")["assigner"], "none");
}

// Station queues (tasks.queues, tasks/station_queues.hpp): at most `capacity` AGVs head for
// a station's cell at once, the others wait on queue cells; the run stays clean and flows.
TEST(ControllerLifelong, StationQueuesAdmitOneAgvPerStation)
{
  Config cfg = lifelong_config("queues", 200);
  cfg.tasks.queue_capacity = 1;
  cfg.tasks.queue_length = 3;
  cfg.output.queue_trace = 50;
  Controller c(cfg);
  const Metrics m = c.run();
  expect_clean_lifelong_run(cfg, c, m);
  EXPECT_LE(m.max_heading, 1);   // 16 AGVs, 4 stations: without queues up to 5 at once
  EXPECT_GT(m.queued_ticks, 20); // AGV-ticks standing on their queue cell
  EXPECT_GE(m.errands_finished, 10);
  // output.queue_trace (tasks/queue_trace.hpp): a line per station every 50 ticks; at most one
  // AGV admitted; the completions it counts at stations are the run's (every errand cell is one).
  {
    std::ifstream in(cfg.output.dir + "/queue_trace.txt");
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line.rfind("# t station", 0), 0u) << line;
    int lines = 0;
    long done = 0;
    while (std::getline(in, line)) {
      ++lines;
      std::istringstream s(line);
      long t = 0;
      int station = -1;
      s >> t >> station;
      EXPECT_EQ(t % 50, 0) << line;
      EXPECT_EQ(station, (lines - 1) % 4) << line;
      const size_t d = line.find(" done ");
      ASSERT_NE(d, std::string::npos) << line;
      done += std::stol(line.substr(d + 6));
      const std::string adm = line.substr(line.find("admitted["), line.find(']') - line.find("admitted["));
      EXPECT_LE(std::count(adm.begin(), adm.end(), '@'), 1) << line;
    }
    EXPECT_EQ(lines, 4 * 4);  // ticks 50, 100, 150, 200; 4 stations
    const nlohmann::json log = read_json(cfg.output.dir + "/lifelong.json");
    long by_200 = 0;
    for (const auto& e : log["events"]) by_200 += e[0].get<long>() <= 200;
    EXPECT_EQ(done, by_200);
  }
  const nlohmann::json mj = read_json(cfg.output.dir + "/metrics.json");
  EXPECT_EQ(mj["lifelong"]["queues"]["maxHeading"], m.max_heading);
  // tasks.queues.fifo reaches the task layer's queues (default: oldest request first).
  for (bool fifo : {true, false}) {
    Config q = cfg;
    q.tasks.queue_fifo = fifo;
    const auto tm = make_task_manager(q, c.map(), make_task_file(q, c.map()));
    ASSERT_NE(tm->queues(), nullptr);
    EXPECT_EQ(tm->queues()->options().fifo, fifo);
  }
}

// One-way queue lanes (tasks.queues.one_way, tasks/station_queues.hpp one_way_queue_lanes): the
// run plans on a graph where each station's queue lane leads only towards the station, so no
// AGV drives up a lane; off, AGVs do (the way out of a station runs up its lane here). On the
// small warehouse the lanes are the only links between aisles: refused with a one-line error.
TEST(ControllerLifelong, OneWayQueueLanesAreNeverDrivenAgainst)
{
  std::vector<long> against;
  std::optional<planner::Graph> lanes;  // the lanes laid on the net's two-way graph (the off run's)
  for (bool one_way : {false, true}) {
    // The large warehouse with queues (8 cells down each station's picking aisle), 60 AGVs:
    // the small one's lanes are the only links between its aisles (one_way refuses it).
    Config cfg = ctest_util::shipped_config("large_warehouse_queues.yaml", one_way ? "oneway_on" : "oneway_off", 300, 20);
    cfg.fleet.count = 60;
    cfg.tasks.queue_one_way = one_way;
    Controller c(cfg);
    const Metrics m = c.run();
    expect_clean_lifelong_run(cfg, c, m);  // the executed plan is valid on the run's graph
    EXPECT_GE(m.errands_finished, 10);
    EXPECT_EQ(c.map().graph.directed(), one_way);
    if (!lanes)
      lanes = tasks::one_way_queue_lanes(c.map().graph, make_task_file(cfg, c.map())->errand_cells(),
                                         task_layer_options(cfg, c.map()).queues);
    long n = 0;  // executed moves against a lane
    const auto& plan = c.plan();
    for (size_t t = 1; t < plan.size(); ++t)
      for (size_t a = 0; a < plan[t].size(); ++a)
        n += plan[t][a] != plan[t - 1][a] && !lanes->adjacent(plan[t - 1][a], plan[t][a]);
    against.push_back(n);
  }
  EXPECT_GT(against[0], 0);  // off: AGVs drive up the lanes
  EXPECT_EQ(against[1], 0);
  Config small = lifelong_config("oneway_small", 10);
  small.tasks.queue_capacity = 1;
  small.tasks.queue_length = 3;
  small.tasks.queue_one_way = true;
  try {
    Controller c(small);
    c.run();
    ADD_FAILURE() << "expected a refusal";
  } catch (const ConfigError& e) {
    // Named as in the net: the station's SUMO stop.
    EXPECT_NE(std::string(e.what()).find("tasks.queues.one_way: one-way queue lanes: the lane of the station at '"), std::string::npos)
        << e.what();
  }
}

// Parking (tasks.parking, tasks/parking.hpp): idle AGVs end on parking cells, not where
// their last errand left them.
TEST(ControllerLifelong, IdleAgvsEndOnParkingCells)
{
  Config cfg = lifelong_config("parking", 150);
  Config y = parse_config(kNetAdd +
                              "fleet: {count: 6, seed: 4}\n"
                              "tasks:\n  mode: lifelong\n  assignment: pool\n  pool_size: 2\n"
                              "  random: {count: 50, errands: 2}\n"
                              "  parking: [{lane: c0r0_c0r1_0, pos: 2}, {lane: c0r0_c0r1_0, pos: 4}, {lane: c0r0_c0r1_0, pos: 6},"
                              " {lane: c3r0_c3r1_0, pos: 2}, {lane: c3r0_c3r1_0, pos: 4}, {lane: c3r0_c3r1_0, pos: 6}]\n",
                          "t.yaml", RTLACAM_CONFIGS);
  y.output = cfg.output;
  y.run = cfg.run;
  y.planner = cfg.planner;
  Controller c(y);
  const Metrics m = c.run();
  expect_clean_lifelong_run(y, c, m);
  EXPECT_GE(m.idle_at_end, 4);  // two tasks at a time for six AGVs
  // All but those just freed by the last two completions stand on a parking cell (without
  // parking: none).
  EXPECT_GE(m.parked_at_end, m.idle_at_end - 2);
  EXPECT_GE(m.errands_finished, 4);
  // On the cells listed, read back from the executed plan (busy AGVs may stand there too).
  const std::vector<planner::Vertex> park = parking_cells(y, c.map());
  int on_parking = 0;
  for (planner::Vertex v : c.plan().back()) on_parking += std::count(park.begin(), park.end(), v) > 0;
  EXPECT_GE(on_parking, m.idle_at_end - 2);
}

TEST(ControllerLifelong, ParkingAndQueueErrorsAreOneLine)
{
  const std::string ll = "fleet: {count: 2}\ntasks:\n  mode: lifelong\n";
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, length: -1}\n"),
            "t.yaml: tasks.queues.length: must be in 0..1000000, got -1");
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 2, admission: 1}\n"),
            "t.yaml: tasks.queues.admission: must be >= capacity (2), 0 or -1, got 1");
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: 3\n"),
            "t.yaml: tasks.queues: expected a mapping {capacity: K, length: L, admission: A, fifo: B, clear_after: N, jam_after: N, one_way: B, in_line: B, leavers_first: B, idle_clear: B}");
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, jam_after: -1}\n"),
            "t.yaml: tasks.queues.jam_after: must be in 0..1000000000, got -1");
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, one_way: 2}\n"),
            "t.yaml: tasks.queues.one_way: expected true or false, got '2'");
  EXPECT_EQ(config_error(kNetAdd + ll + "output: {queue_trace: -3}\n"), "t.yaml: output.queue_trace: must be in 0..1073741824, got -3");
  {
    const Config d = parse_config(kNetAdd + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS);
    EXPECT_EQ(d.tasks.queue_jam_after, 0);  // both off by default
    EXPECT_FALSE(d.tasks.queue_one_way);
    const Config e = parse_config(kNetAdd + ll + "  queues: {capacity: 1, jam_after: 80, one_way: true}\n", "t.yaml", RTLACAM_CONFIGS);
    EXPECT_EQ(e.tasks.queue_jam_after, 80);
    EXPECT_TRUE(e.tasks.queue_one_way);
  }
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, clear_after: -5}\n"),
            "t.yaml: tasks.queues.clear_after: must be in 0..1000000000, got -5");
  EXPECT_EQ(parse_config(kNetAdd + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_clear_after, 0);
  EXPECT_EQ(parse_config(kNetAdd + ll + "  queues: {capacity: 1, clear_after: 20}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_clear_after, 20);
  EXPECT_FALSE(parse_config(kNetAdd + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_in_line);
  EXPECT_TRUE(parse_config(kNetAdd + ll + "  queues: {capacity: 1, in_line: true}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_in_line);
  // In line by default with epibt (session 38), and `in_line: false` keeps request order.
  const std::string ep = "planner: {solver: epibt}\n";
  EXPECT_TRUE(parse_config(kNetAdd + ep + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_in_line);
  EXPECT_FALSE(parse_config(kNetAdd + ep + ll + "  queues: {capacity: 1, in_line: false}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_in_line);
  EXPECT_FALSE(parse_config(kNetAdd + "planner: {solver: pibt-rot}\n" + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS)
                   .tasks.queue_in_line);
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, in_line: 3}\n").rfind("t.yaml: tasks.queues.in_line: ", 0), 0u);
  // Idle AGVs off the cells beside a mouth (session 38): off by default, epibt too.
  EXPECT_FALSE(parse_config(kNetAdd + ep + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_idle_clear);
  EXPECT_FALSE(parse_config(kNetAdd + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_idle_clear);
  EXPECT_TRUE(parse_config(kNetAdd + ll + "  queues: {capacity: 1, idle_clear: true}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_idle_clear);
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, idle_clear: 2}\n"),
            "t.yaml: tasks.queues.idle_clear: expected true or false, got '2'");
  EXPECT_FALSE(parse_config(kNetAdd + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_leavers_first);
  EXPECT_TRUE(parse_config(kNetAdd + ll + "  queues: {capacity: 1, clear_after: 20, leavers_first: true}\n", "t.yaml", RTLACAM_CONFIGS)
                  .tasks.queue_leavers_first);
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, leavers_first: 2}\n"),
            "t.yaml: tasks.queues.leavers_first: expected true or false, got '2'");
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, leavers_first: true}\n"),
            "t.yaml: tasks.queues.leavers_first: needs clear_after > 0 (it acts while a station clears its pocket)");
  EXPECT_EQ(config_error(kNetAdd + ll + "  queues: {capacity: 1, fifo: maybe}\n"),
            "t.yaml: tasks.queues.fifo: expected true or false, got 'maybe'");
  EXPECT_TRUE(parse_config(kNetAdd + ll + "  queues: {capacity: 1}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_fifo);
  EXPECT_FALSE(parse_config(kNetAdd + ll + "  queues: {capacity: 1, fifo: false}\n", "t.yaml", RTLACAM_CONFIGS).tasks.queue_fifo);
  // The stall rules (tasks/urgency.hpp): integers >= 0, read into the task layer's options.
  EXPECT_EQ(config_error(kNetAdd + ll + "  urgency: {swap_after: -1}\n"),
            "t.yaml: tasks.urgency.swap_after: must be in 0..1000000000, got -1");
  EXPECT_EQ(config_error(kNetAdd + ll + "  urgency: {head_after: soon}\n"),
            "t.yaml: tasks.urgency.head_after: expected an integer, got 'soon'");
  EXPECT_EQ(config_error(kNetAdd + ll + "  urgency: {load_cost: -2}\n"),
            "t.yaml: tasks.urgency.load_cost: must be in 0..1000000, got -2");
  EXPECT_EQ(config_error(kNetAdd + ll + "  urgency: {pocket_cost: -3}\n"),
            "t.yaml: tasks.urgency.pocket_cost: must be in 0..1000000, got -3");
  EXPECT_EQ(config_error(kNetAdd + ll + "  urgency: {drop_hints: 2}\n"),
            "t.yaml: tasks.urgency.drop_hints: expected true or false, got '2'");
  EXPECT_EQ(config_error(kNetAdd + ll + "  urgency: {mouth_cost: 255}\n"),
            "t.yaml: tasks.urgency.mouth_cost: must be in 0..254, got 255");
  EXPECT_EQ(config_error(kNetAdd + ll + "  urgency: {sticky: often}\n"),
            "t.yaml: tasks.urgency.sticky: expected true or false, got 'often'");
  {
    const Config c = parse_config(kNetAdd + ll + "  urgency: {swap_after: 30, head_after: 60, load_cost: 10, pocket_cost: 100, drop_hints: true}\n",
                                  "t.yaml", RTLACAM_CONFIGS);
    EXPECT_TRUE(c.tasks.urgency_drop_hints);
    EXPECT_EQ(c.tasks.urgency_pocket_cost, 100);
    EXPECT_EQ(c.tasks.urgency_swap_after, 30);
    EXPECT_EQ(c.tasks.urgency_head_after, 60);
    EXPECT_EQ(c.tasks.urgency_load_cost, 10);
    EXPECT_EQ(c.tasks.urgency_mouth_cost, 0);
    EXPECT_FALSE(c.tasks.urgency_sticky);
  }
  {
    const Config c = parse_config(kNetAdd + ll + "  urgency: {mouth_cost: 2, sticky: true}\n", "t.yaml", RTLACAM_CONFIGS);
    EXPECT_EQ(c.tasks.urgency_mouth_cost, 2);
    EXPECT_TRUE(c.tasks.urgency_sticky);
  }
  EXPECT_EQ(config_error(kNetAdd + ll + "  parking: maybe\n"),
            "t.yaml: tasks.parking: expected true (the parkingAreas of sumo.additional), false or a list of cells, got 'maybe'");
  EXPECT_EQ(config_error(kNetAdd + "fleet: {count: 2}\ntasks: {parking: true}\n"),
            "t.yaml: tasks.parking: only with tasks.mode: lifelong");
  // parking: true reads the parkingAreas; one on a lane gridify dropped is named.
  EXPECT_EQ(run_error(kNetAdd + ll + "  parking: true\n"), "(no error)");
  EXPECT_EQ(run_error(kNet + ll + "  pickups: [3]\n  drops: [4]\n  parking: true\n"),
            "t.yaml: tasks.parking: true, but there is no sumo.additional");
  EXPECT_EQ(run_error("sumo:\n  net: ../sumo_scenarios/small_oneway.net.xml\n"
                      "  additional: ../sumo_scenarios/small_oneway.add.xml\n"
                      "grid: {drop_one_way: true}\n" + ll + "  pickups: [3]\n  drops: [4]\n  parking: true\n"),
            "t.yaml: tasks.parking: parkingArea 'park0' is on a lane gridify dropped (<parkingArea> on lane 'c0r0_c0r1_0': "
            "the lane was dropped from the graph)");
}

TEST(ControllerLifelong, HungarianPoolRuns)
{
  Config cfg = lifelong_config("hungarian", 100);
  cfg.tasks.assigner = "hungarian";
  cfg.fleet.count = 8;
  cfg.tasks.pool_size = 0;  // 1.5 x fleet
  cfg.tasks.reassign = true;
  Controller c(cfg);
  const Metrics m = c.run();
  expect_clean_lifelong_run(cfg, c, m);
  EXPECT_GE(m.errands_finished, 5);
  const nlohmann::json j = read_json(cfg.output.dir + "/lifelong.json");
  EXPECT_EQ(j["assigner"], "hungarian");
  EXPECT_EQ(j["reassign"], true);
  EXPECT_TRUE(j["numReassignments"].is_number_integer());
}

TEST(ControllerLifelong, TaskFileBuilders)
{
  const tasks::TaskFile a = tasks::random_task_file({{1, 2}, {7, 8, 9}}, 50, 3, 5);
  const tasks::TaskFile b = tasks::random_task_file({{1, 2}, {7, 8, 9}}, 50, 3, 5);
  ASSERT_EQ(a.size(), 50);
  EXPECT_EQ(a.tasks, b.tasks);  // deterministic per seed
  std::set<int> first, second;
  for (const auto& t : a.tasks) {
    ASSERT_EQ(t.size(), 3u);
    first.insert(t[0]);
    second.insert(t[1]);
    EXPECT_TRUE(t[2] == 1 || t[2] == 2);  // errands alternate the pools
  }
  EXPECT_EQ(first, (std::set<int>{1, 2}));
  EXPECT_EQ(second, (std::set<int>{7, 8, 9}));
  EXPECT_NE(tasks::random_task_file({{1, 2}, {7, 8, 9}}, 50, 3, 6).tasks, a.tasks);
  EXPECT_THROW(tasks::random_task_file({{1}, {}}, 5, 2, 0), std::invalid_argument);
  EXPECT_THROW(tasks::random_task_file({{1}}, 0, 2, 0), std::invalid_argument);
  const tasks::TaskFile l = tasks::listed_task_file({{3, 4}, {5}});
  EXPECT_EQ(l.size(), 2);
  EXPECT_EQ(l.lines, (std::vector<int>{0, 1}));
  EXPECT_THROW(tasks::listed_task_file({{3}, {}}), std::invalid_argument);
}

TEST(ControllerLifelong, ShippedConfigLoads)
{
  const Config c = load_config(std::string(RTLACAM_CONFIGS) + "/small_warehouse_lifelong.yaml");
  EXPECT_TRUE(c.tasks.lifelong());
  EXPECT_EQ(c.fleet.count, 16);
  EXPECT_EQ(c.tasks.assignment, "pool");
  EXPECT_EQ(c.tasks.pickups.size(), 2u);
  EXPECT_EQ(c.tasks.drops.size(), 2u);
  EXPECT_TRUE(c.tasks.random_tasks);
}

TEST(ControllerLifelong, ConfigErrorsNameTheKeyPath)
{
  struct Case {
    std::string yaml, expect;
  };
  const std::string f = "fleet: {count: 3}\n";
  const std::string ll = f + "tasks:\n  mode: lifelong\n";
  const std::vector<Case> cases = {
      {kNet + f + "tasks: {assignment: pool}\n", "t.yaml: tasks.assignment: only with tasks.mode: lifelong"},
      {kNet + f + "tasks: {pickups: [1]}\n", "t.yaml: tasks.pickups: only with tasks.mode: lifelong"},
      {kNet + ll + "  goals: [1, 2, 3]\n", "t.yaml: tasks.goals: only with tasks.mode: one_shot"},
      {kNet + ll + "  assignment: fifo\n", "t.yaml: tasks.assignment: 'fifo' is not one of pool|roundrobin"},
      {kNet + ll + "  assignment: pool\n  assigner: auction\n", "t.yaml: tasks.assigner: 'auction' is not one of greedy|hungarian"},
      {kNet + ll + "  assigner: greedy\n", "t.yaml: tasks.assigner: only with tasks.assignment: pool"},
      {kNet + ll + "  pool_size: 5\n", "t.yaml: tasks.pool_size: only with tasks.assignment: pool"},
      {kNet + ll + "  assignment: pool\n  pool_size: -1\n", "t.yaml: tasks.pool_size: must be in 0.."},
      {kNet + ll + "  assignment: pool\n  pool_size: many\n", "t.yaml: tasks.pool_size: expected an integer, got 'many'"},
      {kNet + ll + "  assignment: pool\n  k_nearest: 0\n", "t.yaml: tasks.k_nearest: must be in 1.."},
      {kNet + ll + "  reassign: false\n", "t.yaml: tasks.reassign: only with tasks.assignment: pool"},
      {kNet + ll + "  assignment: pool\n  reassign: often\n", "t.yaml: tasks.reassign: expected true or false, got 'often'"},
      {kNet + ll + "  random: {count: 0}\n", "t.yaml: tasks.random.count: must be in 1.."},
      {kNet + ll + "  random: {errands: 0}\n", "t.yaml: tasks.random.errands: must be in 1..100"},
      {kNet + ll + "  random: {count: 5, seed: 2}\n", "t.yaml: tasks.random.seed: unknown key"},
      {kNet + ll + "  random: 5\n", "t.yaml: tasks.random: expected a mapping"},
      {kNet + ll + "  random: {}\n  list: [[1]]\n", "t.yaml: tasks.list: give either tasks.random or tasks.list"},
      {kNet + ll + "  list: []\n", "t.yaml: tasks.list: expected a non-empty list of tasks"},
      {kNet + ll + "  list: [[1, 2], []]\n", "t.yaml: tasks.list[1]: a task needs at least one errand cell"},
      {kNet + ll + "  list: [[1, [2]]]\n", "t.yaml: tasks.list[0][1]: expected a cell id, a station/junction id or {lane: L, pos: P}"},
      {kNet + ll + "  list: [1]\n", "t.yaml: tasks.list[0]: expected a list of cells"},
      {kNet + ll + "  pickups: pickup1\n", "t.yaml: tasks.pickups: expected a list of cells"},
      {kNet + ll + "  pickups: []\n", "t.yaml: tasks.pickups: must list at least one cell"},
      {kNet + ll + "  drops: [{lane: x}]\n", "t.yaml: tasks.drops[0].pos: missing"},
      {kNet + ll + "  drops: [{pos: 1}]\n", "t.yaml: tasks.drops[0].lane: missing"},
      {kNet + ll + "  drops: [{lane: x, pos: -1}]\n", "t.yaml: tasks.drops[0].pos: must be >= 0"},
      {kNet + ll + "  drops: [{lane: x, pos: 1, side: left}]\n", "t.yaml: tasks.drops[0].side: unknown key"},
      {kNet + ll + "  log: out/x.json\n", "t.yaml: tasks.log: expected a file name"},
      {kNet + ll + "  mode2: 1\n", "t.yaml: tasks.mode2: unknown key"},
  };
  for (const Case& c : cases) {
    const std::string msg = config_error(c.yaml);
    EXPECT_EQ(msg.rfind(c.expect, 0), 0u) << "yaml:\n" << c.yaml << "\ngot: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(ControllerLifelong, CellErrorsNeedTheGraph)
{
  const std::string ll = "fleet: {count: 2}\ntasks:\n  mode: lifelong\n";
  EXPECT_EQ(run_error(kNet + ll), "t.yaml: tasks.pickups: missing, and there is no sumo.additional with stations");
  EXPECT_EQ(run_error(kNet + ll + "  pickups: [3]\n  drops: [nowhere]\n"),
            "t.yaml: tasks.drops[0]: 'nowhere' is neither a cell id, a station nor a junction of the graph");
  EXPECT_EQ(run_error(kNet + ll + "  pickups: [3, 999]\n  drops: [4]\n"),
            "t.yaml: tasks.pickups[1]: cell 999 is not on the graph (cells 0..61)");
  EXPECT_EQ(run_error(kNet + ll + "  list: [[3, {lane: nolane_0, pos: 1}]]\n"),
            "t.yaml: tasks.list[0][1]: lane 'nolane_0' is not a lane of a kept aisle of the graph");
  EXPECT_EQ(run_error(kNet + ll + "  random: {errands: 1}\n  pickups: [{lane: c1r0_pick1_0, pos: 40}]\n")
                .rfind("t.yaml: tasks.pickups[0]: pos 40", 0),
            0u);
  // errands: 1 needs no drops; the stations of kind pickup are the default pickups.
  EXPECT_EQ(run_error(kNetAdd + ll + "  random: {errands: 1}\n"), "(no error)");
}

// A long lifelong run keeps only the recent part of its executed plan in memory
// (executed_plan.hpp): plan.txt and the physical bound are the same as with all of it kept,
// lockstep and adg-follow (replans included).
TEST(ControllerLifelong, BoundedPlanMemoryWritesTheSamePlan)
{
  for (const char* file : {"small_warehouse_lifelong.yaml", "small_warehouse_lifelong_agv.yaml"}) {
    std::string txt[2];
    double bound[2];
    for (int keep : {1 << 20, 3}) {
      Config cfg = load_config(std::string(RTLACAM_CONFIGS) + "/" + file);
      cfg.output.dir = temp_dir(std::string("keep") + std::to_string(keep) + file);
      cfg.run.progress_s = 0;
      cfg.run.max_ticks = 120;
      cfg.planner.budget_ms = 0;
      cfg.planner.expansions = 20;
      cfg.sumo.outputs = {};
      cfg.output.plan_keep = keep;
      Controller c(cfg);
      const Metrics m = c.run();
      ASSERT_EQ(m.error, "") << file;
      std::ifstream in(cfg.output.dir + "/plan.txt");
      for (std::string line; std::getline(in, line);)
        if (line.rfind("comp_time=", 0) != 0) txt[keep == 3] += line + '\n';  // a timing
      bound[keep == 3] = m.plan_bound_ticks;
      if (keep == 3) {
        EXPECT_LT(c.plan().size(), 40u) << file;  // the rest went to plan.txt
      }
      EXPECT_FALSE(fs::exists(cfg.output.dir + "/.plan.txt.part")) << file;
    }
    EXPECT_GT(std::count(txt[0].begin(), txt[0].end(), '\n'), 60) << file;  // more than kept
    EXPECT_TRUE(txt[0] == txt[1]) << file;
    EXPECT_DOUBLE_EQ(bound[0], bound[1]) << file;
  }
}

TEST(ControllerLifelong, EpochStartsReadLowerBoundsPastTheStepDeadline)
{
  // run.epoch_in_budget: an epoch start (new goals) is the next SUMO step's planning, so the
  // distance reads of its set_goals stop growing tables at that step's deadline and answer
  // lower bounds past it (planner/dist_cache.hpp). A budget that rounds to 0 ns puts the
  // deadline at the epoch start itself: every read that would grow a table is then a lower
  // bound, deterministically, however loaded the box (no timing threshold). Off: the epoch
  // start has no deadline and every read is exact. Both loops: lockstep starts its epochs
  // at the tick's start, adg-follow in its commits (run.plan_completions, run.hpp).
  for (const char* ex : {"lockstep", "adg-follow"}) {
    long long estimates[2] = {0, 0}, epochs[2] = {0, 0};
    for (const bool on : {false, true}) {
      Config cfg = lifelong_config(std::string("epoch_") + ex + (on ? "_on" : "_off"), 120);
      cfg.run.executor = ex;
      cfg.run.epoch_in_budget = on;
      cfg.planner.budget_ms = 1e-7;  // 0.1 ns: the deadline is the step's start
      Controller c(cfg);
      const Metrics m = c.run();
      ASSERT_EQ(m.error, "") << ex << (on ? " on" : " off");
      EXPECT_EQ(m.violations, 0) << ex;
      EXPECT_EQ(m.commands.jumps, 0) << ex;
      ctest_util::expect_no_sumo_collision(cfg.output.dir);
      estimates[on] = m.epoch_estimates;
      epochs[on] = m.epochs;
      EXPECT_EQ(read_json(cfg.output.dir + "/metrics.json")["lifelong"]["epochDistEstimates"].get<long long>(),
                m.epoch_estimates);
    }
    // Both runs start epochs (measured 27-30 in 150 ticks, 2026-11-26), and only the bounded
    // ones read lower bounds (531-621 in 150 ticks; a new goal whose table already reaches
    // its AGV reads none, so no count per epoch is promised).
    EXPECT_GE(epochs[0], 5) << ex;
    EXPECT_GE(epochs[1], 5) << ex;
    EXPECT_EQ(estimates[0], 0) << ex << ": epoch_in_budget off, yet an epoch start read a lower bound";
    EXPECT_GT(estimates[1], 0) << ex << ": epoch_in_budget on, yet the epoch starts read exact distances";
  }
}

// planner.prefetch (tasks::LifelongEpochs::prefetch, as rtlacam-lifelong --prefetch): the
// tables of the goals to come are grown before the run, and at epoch starts the new next
// goals are queued for the SUMO steps' spare budget. Exact tables either way, so the
// decisions stay those of a run without it. Deterministic: 20 expansions per SUMO step; a
// 1000 ms budget no step reaches leaves each step's rest to the queued tables, a 0 ms one
// (no time limit) none. Off: nothing grows ahead of a query. (A 0 ms and a 1000 ms budget
// are not the same search: RT-LaCAM's expansion reserve is on with a time budget only.)
TEST(ControllerLifelong, PrefetchGrowsTheNextGoalsTablesAndKeepsTheDecisions)
{
  std::vector<std::vector<planner::Config>> plans;
  long long pops[3] = {0, 0, 0};
  int i = 0;
  for (const auto& [prefetch, budget_ms] : std::vector<std::pair<bool, double>>{{false, 1000}, {true, 0}, {true, 1000}}) {
    Config cfg = lifelong_config("prefetch" + std::to_string(i), 150);
    cfg.planner.prefetch = prefetch;
    cfg.planner.budget_ms = budget_ms;
    Controller c(cfg);
    const Metrics m = c.run();
    expect_clean_lifelong_run(cfg, c, m);
    EXPECT_GE(m.epochs, 5);
    pops[i++] = m.precompute_pops;
    EXPECT_EQ(read_json(cfg.output.dir + "/metrics.json")["lifelong"]["precomputePops"].get<long long>(), m.precompute_pops);
    plans.push_back(c.plan());
  }
  EXPECT_EQ(pops[0], 0);
  EXPECT_GT(pops[1], 0);         // before the run
  EXPECT_GT(pops[2], pops[1]);   // and in the steps, for the goals each epoch start queued
  EXPECT_TRUE(plans[0] == plans[2]);  // the same budget, the same moves
}

// The task layer of the YAML is tasks::make_task_layer's (one factory for the controller,
// rtlacam-lifelong and Python): every part of TaskLayerOptions comes from its key.
TEST(ControllerLifelong, YamlFillsTheOneTaskLayerFactory)
{
  Config y = parse_config(kNetAdd +
                              "fleet: {count: 6, seed: 4}\n"
                              "tasks:\n  mode: lifelong\n  assignment: pool\n  assigner: hungarian\n  k_nearest: 5\n"
                              "  pool_size: 3\n  reassign: true\n  random: {count: 50, errands: 2}\n"
                              "  queues: {capacity: 2, length: 3, admission: 7, fifo: false}\n"
                              "  urgency: {stalls: false, battery: false}\n"
                              "  parking: [{lane: c0r0_c0r1_0, pos: 2}, {lane: c3r0_c3r1_0, pos: 2}]\n",
                          "t.yaml", RTLACAM_CONFIGS);
  const Config cfg = lifelong_config("layer", 5);
  y.output = cfg.output;
  y.run = cfg.run;
  y.planner = cfg.planner;
  Controller c(y);
  ASSERT_EQ(c.run().error, "");  // the net gridified: the map the cells resolve on
  const tasks::TaskLayerOptions o = task_layer_options(y, c.map());
  EXPECT_EQ(o.mode, "pool");
  EXPECT_EQ(o.assigner, "hungarian");
  EXPECT_EQ(o.k_nearest, 5);
  EXPECT_EQ(o.pool_size, 3);
  EXPECT_TRUE(o.reassign);
  EXPECT_EQ(o.queues.capacity, 2);
  EXPECT_EQ(o.queues.length, 3);
  EXPECT_EQ(o.queues.admission, 7);
  EXPECT_FALSE(o.queues.fifo);
  EXPECT_FALSE(o.urgency.stalls);
  EXPECT_TRUE(o.parking.on);
  EXPECT_EQ(o.parking.cells, parking_cells(y, c.map()));
  EXPECT_FALSE(o.battery.on);
  const auto tm = make_task_manager(y, c.map(), make_task_file(y, c.map()));
  EXPECT_EQ(tm->mode(), "pool");
  ASSERT_NE(tm->queues(), nullptr);
  EXPECT_EQ(tm->queues()->options().admission, 7);
  EXPECT_FALSE(tm->queues()->options().fifo);
  ASSERT_NE(tm->parking(), nullptr);
  EXPECT_EQ(tm->parking()->cells(), o.parking.cells);
  // Pool size 0: ceil(1.5 x fleet.count); stalls auto: on with queues.
  y.tasks.pool_size = 0;
  y.tasks.urgency_stalls = -1;
  EXPECT_EQ(task_layer_options(y, c.map()).pool_size, 9);
  EXPECT_TRUE(task_layer_options(y, c.map()).urgency.stalls);
}
