#include "controller/fleet.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <unordered_map>

namespace controller {
namespace {

[[noreturn]] void fail(const Config& cfg, const std::string& key, const std::string& what)
{
  throw ConfigError(cfg.path + ": " + key + ": " + what);
}

// " (gridify dropped it: <kind> <id>: <reason>)" when `name` (a junction, edge or station
// id) went with something gridify dropped, else "": the cause, not just "not found".
std::string dropped_note(const gridify::CellMap& map, const std::string& name)
{
  for (const gridify::Dropped& d : map.dropped) {
    bool hit = d.id == name;
    for (const std::string& m : d.members) hit = hit || m == name;
    if (hit) return " (gridify dropped it: " + d.kind + " " + d.id + ": " + d.reason + ")";
  }
  return "";
}

}  // namespace

planner::Vertex resolve_cell(const Config& cfg, const gridify::CellMap& map, const CellRef& c)
{
  const int n = map.graph.size();
  if (!c.lane.empty()) {
    double off = 0;
    const planner::Vertex v = map.locate(c.lane, c.pos, &off);
    if (v < 0)
      fail(cfg, c.key, "lane '" + c.lane + "' is not a lane of a kept aisle of the graph" +
                           dropped_note(map, c.lane.substr(0, c.lane.rfind('_'))));
    if (off > map.cell_length)
      fail(cfg, c.key, "pos " + std::to_string(c.pos) + " is " + std::to_string(off) + " m from the nearest cell of lane '" +
                           c.lane + "' (off the lane?)");
    return v;
  }
  if (c.name.empty()) {
    if (c.vertex < 0 || c.vertex >= n)
      fail(cfg, c.key, "cell " + std::to_string(c.vertex) + " is not on the graph (cells 0.." + std::to_string(n - 1) + ")");
    return c.vertex;
  }
  for (const gridify::Station& s : map.stations)
    if (s.id == c.name) return s.cell;
  planner::Vertex v = map.junction_cell(c.name);
  if (v >= 0) return v;
  fail(cfg, c.key, "'" + c.name + "' is neither a cell id, a station nor a junction of the graph" + dropped_note(map, c.name));
}

namespace {

std::vector<planner::Vertex> resolve_all(const Config& cfg, const gridify::CellMap& map,
                                         const std::vector<CellRef>& refs, const char* what)
{
  std::vector<planner::Vertex> out;
  std::unordered_map<planner::Vertex, const CellRef*> seen;
  for (const CellRef& r : refs) {
    planner::Vertex v = resolve_cell(cfg, map, r);
    auto [it, fresh] = seen.emplace(v, &r);
    if (!fresh) fail(cfg, r.key, "cell " + std::to_string(v) + " is already the " + what + " of " + it->second->key);
    out.push_back(v);
  }
  return out;
}

std::vector<planner::Vertex> random_cells(const Config& cfg, const gridify::CellMap& map, uint64_t seed,
                                          const char* key)
{
  const int n = map.graph.size();
  if (cfg.fleet.count > n)
    fail(cfg, key, std::to_string(cfg.fleet.count) + " AGVs but the graph has only " + std::to_string(n) + " cells");
  std::vector<planner::Vertex> all(n);
  std::iota(all.begin(), all.end(), 0);
  // Partial Fisher-Yates with an explicit mt19937_64 draw: the same cells on every platform
  // (std::shuffle/uniform_int_distribution are implementation-defined).
  std::mt19937_64 rng(seed);
  for (int i = 0; i < cfg.fleet.count; ++i) {
    int j = i + static_cast<int>(rng() % static_cast<uint64_t>(n - i));
    std::swap(all[i], all[j]);
  }
  all.resize(cfg.fleet.count);
  return all;
}

}  // namespace

int keep_out_of_zones(const planner::Graph& g, const std::vector<std::vector<planner::Vertex>>& zones,
                      planner::Config& cells)
{
  std::vector<uint8_t> zoned(g.size(), 0), taken(g.size(), 0);
  for (const auto& z : zones)
    for (planner::Vertex v : z) zoned[v] = 1;
  for (planner::Vertex v : cells) taken[v] = 1;
  int moved = 0;
  std::vector<int> seen(g.size(), -1);
  for (size_t zi = 0; zi < zones.size(); ++zi) {
    std::vector<uint8_t> in(g.size(), 0);
    for (planner::Vertex v : zones[zi]) in[v] = 1;
    bool kept = false;
    for (size_t i = 0; i < cells.size(); ++i) {
      if (!in[cells[i]]) continue;
      if (!kept) {
        kept = true;
        continue;
      }
      // Nearest free cell outside every zone, breadth-first along arcs (stamped marks).
      const int stamp = static_cast<int>(zi * cells.size() + i);
      std::vector<planner::Vertex> queue{cells[i]};
      seen[cells[i]] = stamp;
      for (size_t h = 0; h < queue.size(); ++h) {
        const planner::Vertex u = queue[h];
        if (!zoned[u] && !taken[u]) {
          taken[cells[i]] = 0, taken[u] = 1, cells[i] = u, ++moved;
          break;
        }
        for (planner::Vertex w : g.neighbors(u))
          if (seen[w] != stamp) seen[w] = stamp, queue.push_back(w);
      }
    }
  }
  return moved;
}

planner::Instance make_instance(const Config& cfg, const gridify::CellMap& map)
{
  planner::Instance ins;
  ins.source = cfg.path;
  ins.starts = cfg.fleet.random_starts ? random_cells(cfg, map, cfg.fleet.seed, "fleet.count")
                                       : resolve_all(cfg, map, cfg.fleet.starts, "start");
  if (cfg.tasks.lifelong()) ins.goals = ins.starts;  // goals come from the task layer
  else
    ins.goals = cfg.tasks.random_goals ? random_cells(cfg, map, cfg.tasks.seed, "fleet.count")
                                       : resolve_all(cfg, map, cfg.tasks.goals, "goal");
  try {
    ins.check(map.graph);
  } catch (const std::exception& e) {
    fail(cfg, "fleet", e.what());
  }
  return ins;
}

}  // namespace controller
