#include "tasks/battery.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>

namespace tasks {

Battery::Battery(const planner::Graph& g, BatteryOptions options, std::vector<Charger> chargers,
                 std::vector<std::pair<double, double>> xy)
    : g_(g), options_(options), chargers_(std::move(chargers)), xy_(std::move(xy)), charger_of_(g.size(), -1),
      seen_(g.size(), 0)
{
  if (xy_.size() != static_cast<size_t>(g.size())) throw std::invalid_argument("Battery: one cell centre per vertex needed");
  if (const std::string why = battery_problem(options_); !why.empty()) throw std::invalid_argument("Battery: " + why);
  for (const Charger& c : chargers_)
    if (c.cell < 0 || c.cell >= g.size()) throw std::invalid_argument("Battery: charger '" + c.id + "' is not a vertex");
  for (size_t i = 0; i < chargers_.size(); ++i)
    if (charger_of_[chargers_[i].cell] < 0) charger_of_[chargers_[i].cell] = static_cast<int>(i);
  claimed_by_.assign(chargers_.size(), -1);
  reserved_.assign(g.size(), 0);
  dead_end_.assign(chargers_.size(), 0);
  for (size_t i = 0; i < chargers_.size(); ++i) {
    reserved_[chargers_[i].cell] = 1;
    const std::vector<planner::Vertex> corridor = dead_end_corridor(g, chargers_[i].cell);
    dead_end_[i] = !corridor.empty();
    for (planner::Vertex v : corridor) reserved_[v] = 1;
  }
  if ((options_.reserve_margin > 0 || options_.rematch) && options_.charging) plan_ways();
  double longest = 0;
  for (planner::Vertex v = 0; v < g.size(); ++v)
    for (planner::Vertex u : g.neighbors(v))
      longest = std::max(longest, std::hypot(xy_[u].first - xy_[v].first, xy_[u].second - xy_[v].second));
  move_wh_ = options_.per_m_wh * longest + options_.per_turn_wh;
}

bool Battery::affords(int a, long long moves, planner::Vertex last) const
{
  if (!options_.task_check || options_.reserve_margin <= 0 || !options_.charging || way_wh_.empty() || charge_.empty())
    return true;
  if (at_target(a)) return true;  // as charged as it gets
  double way = std::numeric_limits<double>::infinity();  // to the nearest charger, claimed or not
  for (size_t i = 0; i < chargers_.size(); ++i) way = std::min(way, way_wh_[i][last]);
  if (!std::isfinite(way)) return true;  // no charger reachable from there: the reserve cannot help
  return charge_[a] >= options_.reserve_margin * (static_cast<double>(moves) * move_wh_ + way);
}

bool Battery::charge_first(int a)
{
  if (!options_.charging || at_target(a)) return false;
  first_[a] = 1;
  return true;
}

void Battery::plan_ways()
{
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int n = g_.size();
  auto len = [&](planner::Vertex u, planner::Vertex v) {
    return std::hypot(xy_[v].first - xy_[u].first, xy_[v].second - xy_[u].second);
  };
  way_wh_.assign(chargers_.size(), std::vector<double>(n, kInf));
  way_m_.assign(chargers_.size(), std::vector<double>(n, kInf));
  std::vector<double> metres(n);
  std::vector<planner::Vertex> next(n);  // the first cell of v's way (towards the charger)
  std::vector<int> turns(n);
  std::vector<planner::Vertex> order;  // settled, nearest first
  using Item = std::pair<double, planner::Vertex>;
  for (size_t i = 0; i < chargers_.size(); ++i) {
    std::fill(metres.begin(), metres.end(), kInf);
    std::fill(next.begin(), next.end(), -1);
    order.clear();
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    metres[chargers_[i].cell] = 0;
    open.push({0.0, chargers_[i].cell});
    while (!open.empty()) {
      const auto [d, v] = open.top();
      open.pop();
      if (d > metres[v]) continue;
      order.push_back(v);
      for (planner::Vertex u : g_.in_neighbors(v))  // u -> v: a way from u runs through v
        if (const double du = d + len(u, v); du < metres[u] - 1e-12) metres[u] = du, next[u] = v, open.push({du, u});
    }
    // Turns along each way, nearest first (the rest of a way is settled before it).
    for (planner::Vertex v : order) {
      const planner::Vertex w = next[v];
      turns[v] = 0;
      if (w < 0 || next[w] < 0) continue;
      const double ax = xy_[w].first - xy_[v].first, ay = xy_[w].second - xy_[v].second;
      const double bx = xy_[next[w]].first - xy_[w].first, by = xy_[next[w]].second - xy_[w].second;
      const bool turn = ax * bx + ay * by < std::cos(M_PI / 4) * std::hypot(ax, ay) * std::hypot(bx, by);  // as step() counts
      turns[v] = turns[w] + turn;
    }
    for (planner::Vertex v : order) way_m_[i][v] = metres[v];
    for (planner::Vertex v : order)
      way_wh_[i][v] = options_.per_m_wh * metres[v] + (v == chargers_[i].cell ? 0 : options_.per_turn_wh * (turns[v] + 1));
  }
}

bool Battery::short_of_reserve(int a) const
{
  if (options_.reserve_margin <= 0 || way_wh_.empty() || last_.empty()) return false;
  const planner::Vertex v = last_[a];
  double free = std::numeric_limits<double>::infinity(), any = free;
  for (size_t i = 0; i < chargers_.size(); ++i) {
    any = std::min(any, way_wh_[i][v]);
    if (claimed_by_[i] < 0 || claimed_by_[i] == a) free = std::min(free, way_wh_[i][v]);
  }
  const double need = std::isfinite(free) ? free : any;  // every charger taken: it waits for the nearest
  return std::isfinite(need) && charge_[a] < options_.reserve_margin * need;
}

std::string battery_problem(const BatteryOptions& o)
{
  auto num = [](double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", x);
    return std::string(b);
  };
  if (!(o.capacity_wh > 0)) return "capacity_wh: must be > 0, got " + num(o.capacity_wh);
  if (!(o.per_m_wh >= 0)) return "per_m_wh: must be >= 0, got " + num(o.per_m_wh);
  if (!(o.per_turn_wh >= 0)) return "per_turn_wh: must be >= 0, got " + num(o.per_turn_wh);
  for (auto [k, v] : {std::pair<const char*, double>{"initial", o.initial}, {"threshold", o.threshold}, {"target", o.target}})
    if (!(v > 0 && v <= 1)) return std::string(k) + ": is a fraction of capacity_wh: must be in (0, 1], got " + num(v);
  if (o.threshold >= o.target) return "threshold: must be < target (" + num(o.target) + "), got " + num(o.threshold);
  if (!(o.critical >= 0) || o.critical >= o.threshold)
    return "critical: must be >= 0 and < threshold (" + num(o.threshold) + "), got " + num(o.critical);
  if (!(o.reserve_margin >= 0)) return "reserve_margin: must be >= 0 (0: off), got " + num(o.reserve_margin);
  return "";
}

std::vector<planner::Vertex> dead_end_corridor(const planner::Graph& g, planner::Vertex v)
{
  auto around = [&](planner::Vertex x) {  // neighbours either way (a one-way aisle is still a corridor)
    std::vector<planner::Vertex> out(g.neighbors(x).begin(), g.neighbors(x).end());
    for (planner::Vertex u : g.in_neighbors(x))
      if (std::find(out.begin(), out.end(), u) == out.end()) out.push_back(u);
    return out;
  };
  if (around(v).size() > 2) return {};
  std::vector<planner::Vertex> corridor{v}, mouths;
  for (size_t i = 0; i < corridor.size(); ++i)
    for (planner::Vertex u : around(corridor[i])) {
      if (std::find(corridor.begin(), corridor.end(), u) != corridor.end()) continue;
      if (around(u).size() <= 2) corridor.push_back(u);
      else if (std::find(mouths.begin(), mouths.end(), u) == mouths.end()) mouths.push_back(u);
    }
  if (mouths.size() != 1) return {};
  return corridor;
}

int Battery::nearest_free(planner::Vertex from)
{
  ++stamp_;
  std::vector<planner::Vertex> open{from};
  seen_[from] = stamp_;
  for (size_t i = 0; i < open.size(); ++i) {
    const planner::Vertex v = open[i];
    if (const int c = charger_of_[v]; c >= 0 && claimed_by_[c] < 0) return c;
    for (planner::Vertex u : g_.neighbors(v))
      if (seen_[u] != stamp_) {
        seen_[u] = stamp_;
        open.push_back(u);
      }
  }
  return -1;
}

std::vector<int> Battery::step(const planner::Config& positions)
{
  const int n = static_cast<int>(positions.size());
  std::vector<int> done;
  if (last_.empty()) {  // the first call: the start configuration, nothing driven yet
    last_ = positions;
    charge_.assign(n, options_.initial * options_.capacity_wh);
    min_fraction_ = n > 0 ? options_.initial : 1;
    claim_.assign(n, -1);
    first_.assign(n, 0);
    empty_.assign(n, 0);
    dir_x_.assign(n, 0);
    dir_y_.assign(n, 0);
    return done;
  }
  agent_ticks_ += n;
  emptied_.clear();
  for (int a = 0; a < n; ++a) {
    const planner::Vertex u = last_[a], v = positions[a];
    if (u != v) {
      const double dx = xy_[v].first - xy_[u].first, dy = xy_[v].second - xy_[u].second;
      const double len = std::hypot(dx, dy);
      double wh = options_.per_m_wh * len;
      // A turn: the heading changes by more than 45 degrees from the last move's.
      if ((dir_x_[a] != 0 || dir_y_[a] != 0) && len > 0 && (dx * dir_x_[a] + dy * dir_y_[a]) < std::cos(M_PI / 4) * len)
        wh += options_.per_turn_wh;
      if (len > 0) dir_x_[a] = dx / len, dir_y_[a] = dy / len;
      charge_[a] -= wh;
      if (charge_[a] <= 0 && !empty_[a]) empty_[a] = 1, ++ran_empty_, emptied_.push_back(a);
      charge_[a] = std::max(0.0, charge_[a]);
      min_fraction_ = std::min(min_fraction_, charge_[a] / options_.capacity_wh);
    } else if (claim_[a] >= 0 && chargers_[claim_[a]].cell == v) {
      ++charging_ticks_;
      charge_[a] = std::min(options_.capacity_wh, charge_[a] + chargers_[claim_[a]].wh_per_step);
      if (at_target(a)) {
        claimed_by_[claim_[a]] = -1;
        claim_[a] = -1;
        first_[a] = 0;
        done.push_back(a);
      }
    }
  }
  last_ = positions;
  if (options_.rematch && !way_m_.empty()) rematch(positions);
  return done;
}

void Battery::rematch(const planner::Config& positions)
{
  std::vector<int> way;  // agents on their way to a claimed charger
  for (int a = 0; a < static_cast<int>(claim_.size()); ++a)
    if (claim_[a] >= 0 && chargers_[claim_[a]].cell != positions[a]) way.push_back(a);
  for (size_t i = 0; i < way.size(); ++i)
    for (size_t j = i + 1; j < way.size(); ++j) {
      const int a = way[i], b = way[j], ca = claim_[a], cb = claim_[b];
      const planner::Vertex pa = positions[a], pb = positions[b];
      // Only a swap both can drive: one that sends an agent to a charger beyond its charge
      // trades a short way for an empty battery (bench_charging.py seed 3: 13 Wh left,
      // swapped from a charger 5 m away to one 11 m away at 1.5 Wh/m).
      const bool reach = way_wh_[cb][pa] <= charge_[a] && way_wh_[ca][pb] <= charge_[b];
      if (reach && way_m_[cb][pa] + way_m_[ca][pb] < way_m_[ca][pa] + way_m_[cb][pb] - 1e-9) {
        std::swap(claim_[a], claim_[b]);
        claimed_by_[claim_[a]] = a, claimed_by_[claim_[b]] = b;
        ++swaps_;
      }
    }
}

bool Battery::consider(int a, planner::Vertex at)
{
  if (charging(a)) return true;
  if (!wants(a)) return false;
  const int c = nearest_free(at);
  if (c < 0) return false;  // every charger taken: wait idle, try again next step
  claim_[a] = c;
  claimed_by_[c] = a;
  ++errands_;
  return true;
}

}  // namespace tasks
