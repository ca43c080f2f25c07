#include "planner/zones.hpp"

#include <algorithm>

namespace planner {

std::shared_ptr<const Zones> Zones::from_cells(size_t num_vertices, const std::vector<std::vector<Vertex>>& cells)
{
  auto z = std::make_shared<Zones>();
  z->of.assign(num_vertices, {});
  z->count = static_cast<int>(cells.size());
  for (int k = 0; k < z->count; ++k)
    for (Vertex v : cells[k])
      if (v >= 0 && static_cast<size_t>(v) < num_vertices && !z->in(v, k)) z->of[v].push_back(k), z->cells.resize(z->count), z->cells[k].push_back(v);
  z->cells.resize(z->count);
  return z;
}

bool Zones::in(Vertex v, int z) const
{
  return std::find(of[v].begin(), of[v].end(), z) != of[v].end();
}

std::string zone_conflict(const Zones& zones, const Config& from, const Config& to)
{
  std::vector<int> holder(zones.count, -1);
  for (size_t i = 0; i < from.size(); ++i)
    for (const Config* c : {&from, &to})
      for (int z : zones.of[(*c)[i]]) {
        if (holder[z] >= 0 && holder[z] != static_cast<int>(i))
          return "zone " + std::to_string(z) + ": agents " + std::to_string(holder[z]) + " and " + std::to_string(i);
        holder[z] = static_cast<int>(i);
      }
  return "";
}

}  // namespace planner
