#include "planner/rotation/pocket_exit.hpp"

#include <stdexcept>
#include <algorithm>

namespace planner {

void PocketExit::set(const Graph& g, std::vector<Vertex> pocket)
{
  if (!pocket.empty() && pocket.size() != static_cast<size_t>(g.size())) throw std::invalid_argument("pockets: one label per vertex");
  pocket_ = std::move(pocket);
  leaving_list_.clear();
  depth_.assign(pocket_.size(), 0);
  leaving_.assign(pocket_.size(), 0);
  count_.assign(pocket_.size(), 0);
  crowded_.assign(pocket_.size(), 0);
  maxd_.assign(pocket_.size(), 0);
  mouths_.clear();
  // Breadth first from the pocket cells next to the outside (depth 1).
  std::vector<Vertex> front, next;
  for (Vertex v = 0; v < static_cast<Vertex>(pocket_.size()); ++v) {
    if (pocket_[v] < 0) continue;
    for (Vertex u : g.neighbors(v))
      if (pocket_[u] != pocket_[v]) {
        if (depth_[v] == 0) depth_[v] = 1, front.push_back(v);
        if (pocket_[u] < 0) mouths_.emplace_back(pocket_[v], u);
      }
  }
  for (int d = 2; !front.empty(); ++d, front.swap(next)) {
    next.clear();
    for (Vertex v : front)
      for (Vertex u : g.neighbors(v))
        if (pocket_[u] == pocket_[v] && depth_[u] == 0) depth_[u] = d, next.push_back(u);
  }
  for (Vertex v = 0; v < static_cast<Vertex>(pocket_.size()); ++v)
    if (pocket_[v] >= 0) maxd_[pocket_[v]] = std::max(maxd_[pocket_[v]], depth_[v]);
}

void PocketExit::mark(const Config& current, const Config& goals)
{
  for (Vertex p : leaving_list_) leaving_[p] = 0, count_[p] = 0, crowded_[p] = 0;
  leaving_list_.clear();
  if (pocket_.empty()) return;
  for (size_t i = 0; i < current.size(); ++i) {
    const Vertex p = pocket_[current[i]];
    if (p >= 0 && pocket_[goals[i]] != p && !leaving_[p]) leaving_[p] = 1, leaving_list_.push_back(p);
  }
  if (leaving_list_.empty()) return;
  std::vector<char> at(pocket_.size(), 0);  // O(cells) per step, only while someone must leave
  for (Vertex v : current) at[v] = 1;
  for (Vertex v : current)
    if (const Vertex p = pocket_[v]; p >= 0 && leaving_[p] && ++count_[p] >= 2) crowded_[p] = 1;
  for (const auto& [p, m] : mouths_)
    if (leaving_[p] && at[m]) crowded_[p] = 1;
}

}  // namespace planner
