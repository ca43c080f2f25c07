#include "tasks/station_queues.hpp"

#include <algorithm>
#include <queue>
#include <stdexcept>
#include <string>

#include "planner/blocked.hpp"

namespace tasks {

namespace {

// Neighbours either way (a one-way aisle is still a corridor).
std::vector<planner::Vertex> around(const planner::Graph& g, planner::Vertex v)
{
  std::vector<planner::Vertex> out(g.neighbors(v).begin(), g.neighbors(v).end());
  for (planner::Vertex u : g.in_neighbors(v))
    if (std::find(out.begin(), out.end(), u) == out.end()) out.push_back(u);
  return out;
}

}  // namespace

StationQueues::StationQueues(const planner::Graph& g, std::vector<planner::Vertex> stations, QueueOptions o)
    : g_(g), opt_(o), reserved_(g.size(), 0), pocket_of_(g.size(), -1), dist_(g)
{
  std::sort(stations.begin(), stations.end());
  stations.erase(std::unique(stations.begin(), stations.end()), stations.end());
  for (planner::Vertex s : stations) {
    index_[s] = static_cast<int>(st_.size());
    Station k;
    k.cell = s;
    k.mouth = s;
    st_.push_back(std::move(k));
    reserved_[s] = 1;
    pocket_of_[s] = index_[s];
  }
  // Pockets: the corridor (cells with at most 2 neighbours) joined to the station. With one
  // junction at its mouth it is a dead end: reserved with its mouth, and the queue starts
  // beside the mouth. Otherwise (a through aisle, or the station is a junction) only the
  // station is reserved and the queue starts beside it.
  for (Station& k : st_) {
    if (around(g_, k.cell).size() > 2) continue;
    std::vector<planner::Vertex> pocket{k.cell}, mouths;
    std::vector<int> depth{0};
    for (size_t i = 0; i < pocket.size(); ++i)
      for (planner::Vertex u : around(g_, pocket[i])) {
        if (std::find(pocket.begin(), pocket.end(), u) != pocket.end()) continue;
        if (around(g_, u).size() <= 2) {
          pocket.push_back(u);
          depth.push_back(depth[i] + 1);
        } else if (std::find(mouths.begin(), mouths.end(), u) == mouths.end()) {
          mouths.push_back(u);
          if (mouths.size() == 1) k.depth = depth[i] + 1;
        }
      }
    if (mouths.size() != 1) continue;
    k.mouth = mouths[0];
    for (planner::Vertex v : pocket) {
      reserved_[v] = 1;
      if (pocket_of_[v] < 0) pocket_of_[v] = index_[k.cell];
    }
    reserved_[k.mouth] = 1;
  }
  for (Station& k : st_) build_queue(k);
  clear_ = reserved_;
  for (const Station& k : st_)
    if (k.mouth != k.cell)
      for (planner::Vertex u : around(g_, k.mouth)) clear_[u] = 1;
  in_use_.assign(g.size(), 0);
  area_.resize(st_.size());
  for (planner::Vertex v = 0; v < g.size(); ++v)
    if (pocket_of_[v] >= 0) area_[pocket_of_[v]].push_back(v);
  for (size_t i = 0; i < st_.size(); ++i) {
    if (st_[i].mouth != st_[i].cell) area_[i].push_back(st_[i].mouth);
    area_[i].insert(area_[i].end(), st_[i].queue.begin(), st_[i].queue.end());
  }
}

int StationQueues::admission_limit(int i) const
{
  if (opt_.admission < 0) return -1;
  return opt_.admission > 0 ? opt_.admission : opt_.capacity + static_cast<int>(st_[i].queue.size());
}

int StationQueues::station_index(planner::Vertex v) const
{
  auto it = index_.find(v);
  return it == index_.end() ? -1 : it->second;
}

void StationQueues::build_queue(Station& s)
{
  if (opt_.length == 0) return;
  // Moves to the station, searched backwards along arcs, as far as the chain can reach.
  const int limit = s.depth + opt_.length + 1;
  std::unordered_map<planner::Vertex, int> d{{s.cell, 0}};
  std::queue<planner::Vertex> open;
  open.push(s.cell);
  while (!open.empty()) {
    const planner::Vertex v = open.front();
    open.pop();
    if (d[v] >= limit) continue;
    for (planner::Vertex u : g_.in_neighbors(v))
      if (d.emplace(u, d[v] + 1).second) open.push(u);
  }
  if (!d.count(s.mouth)) return;
  // Free corridor cells in a row from u away from the station (u itself included).
  auto run = [&](planner::Vertex u) {
    int n = 0;
    for (planner::Vertex v = u, prev = -1; n < opt_.length && !reserved_[v] && around(g_, v).size() <= 2; ++n) {
      planner::Vertex next = -1;
      for (planner::Vertex w : g_.in_neighbors(v))
        if (w != prev && d.count(w) && d.at(w) == d.at(v) + 1) next = w;
      if (next < 0) return n + 1;
      prev = v, v = next;
    }
    return n;
  };
  planner::Vertex cur = s.mouth;
  while (static_cast<int>(s.queue.size()) < opt_.length) {
    planner::Vertex best = -1;
    int best_run = -1;
    for (planner::Vertex u : g_.in_neighbors(cur)) {
      auto it = d.find(u);
      if (it == d.end() || it->second != d[cur] + 1 || reserved_[u]) continue;
      const int r = run(u);
      if (r > best_run || (r == best_run && u < best)) best = u, best_run = r;
    }
    if (best < 0) break;
    s.queue.push_back(best);
    reserved_[best] = 1;
    cur = best;
  }
}

void StationQueues::in_line(int i, const planner::Config& positions)
{
  Station& s = st_[i];
  auto nearer = [&](int x, int y) { return dist_.from_goal(s.cell, positions[x]) < dist_.from_goal(s.cell, positions[y]); };
  // An admitted agent in the pocket keeps its place (it is past the lane); then only the
  // queue is re-ranked.
  bool fixed = false;
  for (int a : s.admitted) fixed = fixed || pocket_of_[positions[a]] == i;
  if (fixed || s.admitted.empty()) {
    std::stable_sort(s.waiting.begin(), s.waiting.end(), nearer);
    return;
  }
  std::vector<int> line = s.admitted;
  line.insert(line.end(), s.waiting.begin(), s.waiting.end());
  std::stable_sort(line.begin(), line.end(), nearer);
  const long na = static_cast<long>(s.admitted.size());
  s.admitted.assign(line.begin(), line.begin() + na);
  s.waiting.assign(line.begin() + na, line.end());
}

void StationQueues::drop_place(int agent)
{
  Station& s = st_[place_[agent]];
  for (std::vector<int>* l : {&s.admitted, &s.waiting})
    l->erase(std::remove(l->begin(), l->end(), agent), l->end());
  place_[agent] = -1;
}

void StationQueues::apply(const std::vector<planner::Vertex>& errand, const planner::Config& positions,
                          planner::Config& goals, std::vector<char>& unplaced)
{
  const int n = static_cast<int>(errand.size());
  unplaced.assign(n, 0);
  if (static_cast<int>(place_.size()) != n) place_.assign(n, -1), asked_at_.assign(n, -1), asked_.assign(n, 0);
  for (int a = 0; a < n; ++a)
    if (place_[a] >= 0 && errand[a] != st_[place_[a]].cell) drop_place(a);
  for (int a = 0; a < n; ++a)  // a request ends with its errand (done, or the task handed back)
    if (asked_at_[a] >= 0 && errand[a] != st_[asked_at_[a]].cell) asked_at_[a] = -1;
  // Newcomers per station; stations with anybody at them.
  std::unordered_map<int, std::vector<int>> fresh;
  std::vector<int> touched;
  for (int a = 0; a < n; ++a) {
    if (errand[a] < 0) continue;
    const int i = station_index(errand[a]);
    if (i < 0) continue;
    auto [it, added] = fresh.try_emplace(i);
    if (added) touched.push_back(i);
    if (place_[a] < 0) it->second.push_back(a);
  }
  // Agents in a station's pocket that are not admitted there (on their way out, idle ones
  // leaving, passers-by at a through station) hold a place until they are out.
  std::unordered_map<int, int> inside;
  for (int a = 0; a < n; ++a)
    if (const int i = pocket_of_[positions[a]]; i >= 0 && !(place_[a] == i && errand[a] == st_[i].cell &&
                                                              std::find(st_[i].admitted.begin(), st_[i].admitted.end(), a) !=
                                                                  st_[i].admitted.end()))
      ++inside[i];
  auto give_up = [&](size_t i) {
    Station& s = st_[i];
    s.clearing = true;
    ++clearings_;
    for (std::vector<int>* l : {&s.admitted, &s.waiting})
      for (int a : *l) place_[a] = -1, fresh[static_cast<int>(i)].push_back(a);
    s.admitted.clear(), s.waiting.clear();
    if (std::find(touched.begin(), touched.end(), static_cast<int>(i)) == touched.end()) touched.push_back(static_cast<int>(i));
  };
  if (opt_.jam_after > 0) {
    std::vector<char> held;  // per vertex: an agent stands there
    for (size_t i = 0; i < st_.size(); ++i) {
      Station& s = st_[i];
      if (s.clearing && s.jam) {  // until the station's cells are empty, jam_after steps at most
        if (held.empty()) {
          held.assign(g_.size(), 0);
          for (int a = 0; a < n; ++a) held[positions[a]] = 1;
        }
        bool empty = true;
        for (planner::Vertex v : area_[i]) empty = empty && !held[v];
        if (empty || s.cleared_for >= opt_.jam_after) s.clearing = s.jam = false, s.cleared_for = 0;
        continue;
      }
      if (s.clearing || s.admitted.empty()) {
        s.jam_agent = -1;
        continue;
      }
      const int a = s.admitted.front();
      const int32_t d = dist_.from_goal(s.cell, positions[a]);
      if (a != s.jam_agent || d < s.jam_best || pocket_of_[positions[a]] == static_cast<int>(i)) {
        s.jam_agent = a, s.jam_best = d, s.jam_since = 0;
        continue;
      }
      if (++s.jam_since < opt_.jam_after) continue;
      s.jam_agent = -1;
      s.jam = true;
      ++jam_clearings_;
      give_up(i);
    }
  }
  if (opt_.clear_after > 0)
    for (size_t i = 0; i < st_.size(); ++i) {
      Station& s = st_[i];
      if (s.mouth == s.cell) continue;  // no dead end: a leaver can pass on
      if (s.jam) continue;              // a jam clearing ends by its own rule
      const bool leaver = inside.count(static_cast<int>(i)) > 0;
      s.blocked = leaver ? s.blocked + 1 : 0;
      if (!leaver) s.clearing = false;
      if (!s.clearing && s.blocked >= opt_.clear_after) give_up(i);
    }
  for (Station& s : st_) {
    s.cleared_for = s.clearing ? s.cleared_for + 1 : 0;
    clearing_steps_ += s.clearing ? 1 : 0;
    longest_clearing_ = std::max(longest_clearing_, s.cleared_for);
  }
  std::sort(touched.begin(), touched.end());
  std::vector<std::pair<int32_t, int>> order;
  for (int i : touched) {
    Station& s = st_[i];
    if (s.clearing) {  // everybody with an errand here waits beyond the queue until the pocket is empty
      for (int a : fresh[i]) unplaced[a] = 1;
      continue;
    }
    auto room = [&] {
      auto it = inside.find(i);
      return static_cast<int>(s.admitted.size()) + (it == inside.end() ? 0 : it->second) < opt_.capacity;
    };
    if (opt_.in_line) in_line(i, positions);
    while (room() && !s.waiting.empty()) {
      s.admitted.push_back(s.waiting.front());
      s.waiting.erase(s.waiting.begin());
    }
    order.clear();
    for (int a : fresh[i]) order.push_back({dist_.from_goal(s.cell, positions[a]), a});
    std::sort(order.begin(), order.end());  // nearest first
    if (opt_.fifo) {  // stamp the new requests nearest first, then take the oldest first
      for (const auto& [d, a] : order)
        if (asked_at_[a] != i) asked_at_[a] = i, asked_[a] = requests_++;
      std::stable_sort(order.begin(), order.end(),
                       [&](const auto& x, const auto& y) { return asked_[x.second] < asked_[y.second]; });
    }
    size_t k = 0;
    for (; k < order.size() && s.waiting.empty() && room(); ++k) {
      s.admitted.push_back(order[k].second);
      place_[order[k].second] = i;
    }
    if (k < order.size()) {
      const std::vector<planner::Vertex>& q = s.queue;
      for (; k < order.size() && s.waiting.size() < q.size(); ++k) {
        s.waiting.push_back(order[k].second);
        place_[order[k].second] = i;
      }
    }
    for (size_t w = 0; w < s.waiting.size(); ++w) goals[s.waiting[w]] = s.queue[w];
    // Beyond the queue (not sticky): the caller parks them.
    for (; k < order.size(); ++k) unplaced[order[k].second] = 1;
  }
  for (planner::Vertex v : in_use_list_) in_use_[v] = 0;
  in_use_list_.clear();
  for (size_t i = 0; i < st_.size(); ++i)
    if (!st_[i].admitted.empty() || !st_[i].waiting.empty() || st_[i].clearing)
      for (planner::Vertex v : area_[i])
        if (!in_use_[v]) in_use_[v] = 1, in_use_list_.push_back(v);
}

planner::Graph one_way_queue_lanes(const planner::Graph& g, const std::vector<planner::Vertex>& stations,
                                   const QueueOptions& o, const std::function<std::string(planner::Vertex)>& name)
{
  const StationQueues q(g, stations, o);
  std::vector<planner::Vertex> toward(g.size(), -1);  // per queue cell: its next cell towards the station
  for (int i = 0; i < q.num_stations(); ++i) {
    const std::vector<planner::Vertex>& lane = q.queue_cells(i);
    for (size_t k = 0; k < lane.size(); ++k) toward[lane[k]] = k == 0 ? q.mouth(i) : lane[k - 1];
  }
  planner::Graph d = planner::without_arcs(g, [&](planner::Vertex u, planner::Vertex v) {
    if (toward[u] >= 0) return v != toward[u];  // on a lane: towards the station only
    return toward[v] >= 0 && toward[v] == u;    // the way back up a lane (the mouth into q1)
  });
  int before = 0, count = 0;
  g.strong_components(&before);
  const std::vector<int> comp = d.strong_components(&count);
  if (count > before)
    for (int i = 0; i < q.num_stations(); ++i)
      if (comp[q.station(i)] != comp[0] || (!q.queue_cells(i).empty() && comp[q.queue_cells(i).back()] != comp[q.station(i)]))
        throw std::invalid_argument("one-way queue lanes: the lane of the station at " +
                                    (name ? name(q.station(i)) : "cell " + std::to_string(q.station(i))) + " cuts the net (" +
                                    std::to_string(count) + " strongly connected parts)");
  if (count > before) throw std::invalid_argument("one-way queue lanes cut the net (" + std::to_string(count) + " strongly connected parts)");
  return d;
}

}  // namespace tasks
