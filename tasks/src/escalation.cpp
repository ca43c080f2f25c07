#include "tasks/escalation.hpp"

#include <algorithm>
#include <unordered_map>

#include "tasks/task_manager.hpp"
#include "tasks/urgency.hpp"

namespace tasks {

std::vector<char> escalated_agents(const TaskManager& tm)
{
  if (tm.urgency().escalate_after <= 0 || !tm.stalls()) return {};
  std::unordered_map<planner::Vertex, std::pair<long long, int>> top;  // errand cell -> (stall, agent)
  for (int a = 0; a < tm.num_agents(); ++a) {
    if (!tm.escalated(a)) continue;
    const Task* k = tm.task_of(a);
    const long long s = tm.stalls()->longest(tm.now(), k->id);
    auto [it, fresh] = top.try_emplace(k->next_cell(), s, a);
    if (!fresh && s > it->second.first) it->second = {s, a};
  }
  if (top.empty()) return {};
  std::vector<char> esc(tm.num_agents(), 0);
  for (const auto& [cell, t] : top) esc[t.second] = 1;
  return esc;
}

int escalation_focus(const TaskManager& tm, const planner::Config& positions)
{
  // Not on a directed graph: RT-LaCAM moves only along reversible moves until its search has
  // a goal node (rt_lacam.hpp), and a goal only one agent can pass took that search hundreds
  // of ticks there (small_oneway_lifelong, fleet seed 1: no AGV moved from tick 644 on, K 3999
  // of 4000 ticks; hints and pocket clearing still apply).
  if (tm.urgency().escalate_after <= 0 || !tm.stalls() || tm.stalls()->graph().directed()) return -1;
  for (int a = 0; a < tm.num_agents(); ++a)
    if (tm.awaited(a) && battery_urgent(tm, a) && positions[a] != tm.goals()[a]) return -1;
  const std::vector<char> esc = escalated_agents(tm);
  int top = -1;
  long long best = -1;
  for (size_t a = 0; a < esc.size(); ++a) {
    const int i = static_cast<int>(a);
    if (!esc[a] || !tm.heading(i) || positions[i] == tm.goals()[i]) continue;
    const long long s = tm.stalls()->longest(tm.now(), tm.task_of(i)->id);
    if (s > best) best = s, top = i;
  }
  return top;
}

std::vector<char> escalated_pockets(const TaskManager& tm, const std::vector<char>& esc)
{
  std::vector<char> out;
  const std::vector<planner::Vertex>& pocket = tm.dead_end_pockets();
  for (size_t a = 0; a < esc.size(); ++a) {
    if (!esc[a] || !tm.heading(static_cast<int>(a))) continue;
    const planner::Vertex c = tm.task_of(static_cast<int>(a))->next_cell();
    if (c >= static_cast<planner::Vertex>(pocket.size()) || pocket[c] < 0) continue;
    if (out.empty()) out.assign(pocket.size(), 0);
    for (size_t v = 0; v < pocket.size(); ++v)
      if (pocket[v] == pocket[c]) out[v] = 1;
  }
  return out;
}

void escalation_hints(const TaskManager& tm, const planner::Config& positions, std::vector<float>& h)
{
  const std::vector<char> esc = escalated_agents(tm);
  for (size_t a = 0; a < esc.size(); ++a)
    if (esc[a] && tm.heading(static_cast<int>(a))) {
      const long long s = tm.stalls()->longest(tm.now(), tm.task_of(static_cast<int>(a))->id);
      h[a] = std::max(h[a], kEscalatedUrgency + std::min(static_cast<float>(s), kEscalatedSpan - 1));
    }
  const std::vector<char> clear = escalated_pockets(tm, esc);
  if (clear.empty()) return;
  for (int a = 0; a < tm.num_agents(); ++a)
    if (clear[positions[a]] && !clear[tm.goals()[a]]) h[a] = std::max(h[a], kClearingUrgency);
}

planner::Vertex evict_cell(const planner::Graph& g, const std::vector<planner::Vertex>& dead_end_pocket,
                           planner::Vertex from, const std::vector<uint8_t>* avoid)
{
  auto in_pocket = [&](planner::Vertex v) { return dead_end_pocket[v] >= 0; };
  std::vector<char> seen(g.size(), 0);
  std::vector<planner::Vertex> q{from};
  seen[from] = 1;
  for (size_t i = 0; i < q.size(); ++i) {  // breadth first along arcs
    const planner::Vertex v = q[i];
    bool ok = !in_pocket(v) && !(avoid && (*avoid)[v]);
    for (planner::Vertex u : g.neighbors(v)) ok = ok && !in_pocket(u);
    if (ok) return v;
    for (planner::Vertex u : g.neighbors(v))
      if (!seen[u]) seen[u] = 1, q.push_back(u);
  }
  return from;
}

}  // namespace tasks
