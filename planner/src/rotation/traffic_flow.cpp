#include "planner/rotation/traffic_flow.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

namespace planner {

TrafficFlow::TrafficFlow(const RotationDist& dist, size_t agents, Options opt)
    : dist_(dist), opt_(opt), table_(agents), path_(agents), head_(agents, 0)
{
  if (!(opt.contraflow >= 0) || !(opt.vertex >= 0) || opt.contraflow > 1000 || opt.vertex > 1000)
    throw std::invalid_argument("traffic flow: weights must be in 0..1000");
  if (opt.refresh < 0) throw std::invalid_argument("traffic flow: refresh must be >= 0");
  if (!(opt.share > 0) || opt.share > 1) throw std::invalid_argument("traffic flow: share must be in (0, 1]");
  const size_t n = static_cast<size_t>(dist.graph().size());
  flow_.assign(n * 4, 0);
  load_.assign(n, 0);
}

uint32_t TrafficFlow::forward(Vertex v, int o) const
{
  const Vertex u = dist_.ahead(v, o);
  if (u < 0) return kInf;
  const double congestion = opt_.contraflow * flow_[static_cast<size_t>(u) * 4 + static_cast<size_t>(reversed(o))] +
                            opt_.vertex * load_[static_cast<size_t>(u)];
  return kScale * dist_.forward_cost(v, o) + static_cast<uint32_t>(std::lround(kScale * congestion));
}

void TrafficFlow::add_path(int agent)
{
  const std::vector<int32_t>& p = path_[static_cast<size_t>(agent)];
  for (size_t k = head_[static_cast<size_t>(agent)]; k < p.size(); ++k) {
    ++flow_[static_cast<size_t>(p[k])];
    ++load_[static_cast<size_t>(dist_.ahead(p[k] / 4, p[k] % 4))];
  }
}

void TrafficFlow::remove_path(int agent)
{
  const std::vector<int32_t>& p = path_[static_cast<size_t>(agent)];
  for (size_t k = head_[static_cast<size_t>(agent)]; k < p.size(); ++k) {
    --flow_[static_cast<size_t>(p[k])];
    --load_[static_cast<size_t>(dist_.ahead(p[k] / 4, p[k] % 4))];
  }
  path_[static_cast<size_t>(agent)].clear();
  head_[static_cast<size_t>(agent)] = 0;
}

void TrafficFlow::drop(int agent)
{
  remove_path(agent);
  std::vector<uint32_t>().swap(table_[static_cast<size_t>(agent)]);
}

void TrafficFlow::advance(int agent, Vertex v, int o)
{
  std::vector<int32_t>& p = path_[static_cast<size_t>(agent)];
  size_t& k = head_[static_cast<size_t>(agent)];
  if (k >= p.size() || p[k] != v * 4 + o) return;  // off its guide: the next refresh re-plans it
  --flow_[static_cast<size_t>(p[k])];
  --load_[static_cast<size_t>(dist_.ahead(v, o))];
  ++k;
}

std::vector<int32_t> TrafficFlow::path(int agent) const
{
  const std::vector<int32_t>& p = path_[static_cast<size_t>(agent)];
  return {p.begin() + static_cast<std::ptrdiff_t>(head_[static_cast<size_t>(agent)]), p.end()};
}

void TrafficFlow::plan(int agent, Vertex v0, int o0, Vertex goal)
{
  remove_path(agent);
  ++plans_;
  const size_t states = static_cast<size_t>(dist_.graph().size()) * 4;
  std::vector<uint32_t>& t = table_[static_cast<size_t>(agent)];
  t.assign(states, kInf);
  // Backward Dijkstra from the goal cell (any heading) under the current costs.
  heap_.clear();
  const auto later = std::greater<std::pair<uint32_t, int32_t>>();
  for (int o = 0; o < 4; ++o) t[static_cast<size_t>(goal) * 4 + static_cast<size_t>(o)] = 0, heap_.push_back({0, goal * 4 + o});
  const uint32_t turn_cost = turn();
  auto relax = [&](int32_t s, uint64_t d64) {
    const uint32_t d = static_cast<uint32_t>(std::min<uint64_t>(d64, kInf - 1));  // heavy weights saturate, never wrap
    if (d < t[static_cast<size_t>(s)]) {
      t[static_cast<size_t>(s)] = d;
      heap_.push_back({d, s});
      std::push_heap(heap_.begin(), heap_.end(), later);
    }
  };
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    const auto [d, s] = heap_.back();
    heap_.pop_back();
    if (d > t[static_cast<size_t>(s)]) continue;
    const Vertex u = s / 4;
    const int o = s % 4;
    relax(u * 4 + turned_cw(o), uint64_t{d} + turn_cost);  // (u, o + 1) turns counter-clockwise into (u, o)
    relax(u * 4 + turned_ccw(o), uint64_t{d} + turn_cost);  // (u, o - 1) turns clockwise
    const Vertex v = dist_.behind(u, o);  // (v, o) moves forward into u
    if (v >= 0) relax(v * 4 + o, uint64_t{d} + forward(v, o));
  }
  // The guide path: down the table from (v0, o0), forward first on ties.
  std::vector<int32_t>& p = path_[static_cast<size_t>(agent)];
  Vertex v = v0;
  int o = o0;
  for (size_t guard = 0; v != goal && t[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)] != kInf && guard < states; ++guard) {
    const uint32_t here = t[static_cast<size_t>(v) * 4 + static_cast<size_t>(o)];
    const Vertex u = dist_.ahead(v, o);
    const uint32_t f = forward(v, o);
    if (u >= 0 && f != kInf && t[static_cast<size_t>(u) * 4 + static_cast<size_t>(o)] != kInf &&
        f + t[static_cast<size_t>(u) * 4 + static_cast<size_t>(o)] == here) {
      p.push_back(v * 4 + o);
      v = u;
    } else if (turn_cost + t[static_cast<size_t>(v) * 4 + static_cast<size_t>(turned_cw(o))] == here) {
      o = turned_cw(o);
    } else {
      o = turned_ccw(o);
    }
  }
  head_[static_cast<size_t>(agent)] = 0;
  add_path(agent);
}

}  // namespace planner
