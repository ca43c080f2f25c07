#include "tasks/action_model.hpp"

#include <stdexcept>

namespace tasks {

ActionModel parse_action_model(const std::string& s)
{
  if (s == "grid4") return ActionModel::Grid4;
  if (s == "rotation") return ActionModel::Rotation;
  throw std::invalid_argument("unknown action model '" + s + "' (grid4 | rotation)");
}

std::string to_string(ActionModel m) { return m == ActionModel::Rotation ? "rotation" : "grid4"; }

std::string lorr_name(ActionModel m) { return m == ActionModel::Rotation ? "MAPF_T" : "MAPF"; }

int heading_of_move(const planner::Graph& g, planner::Vertex u, planner::Vertex v)
{
  const int dx = g.cell_x(v) - g.cell_x(u), dy = g.cell_y(v) - g.cell_y(u);
  if (dx == 1 && dy == 0) return 0;
  if (dx == 0 && dy == 1) return 1;
  if (dx == -1 && dy == 0) return 2;
  if (dx == 0 && dy == -1) return 3;
  throw std::invalid_argument("not a 4-neighbour move: " + std::to_string(u) + " -> " + std::to_string(v));
}

char grid4_letter(const planner::Graph& g, planner::Vertex u, planner::Vertex v)
{
  if (u == v) return 'W';
  constexpr char kLetter[4] = {'R', 'U', 'L', 'D'};  // PlanViz: U = row + 1 (south)
  return kLetter[heading_of_move(g, u, v)];
}

std::string check_rotation_step(const planner::Graph& g, const planner::Config& pos, const std::vector<int>& heading,
                                const std::string& actions, const planner::Config& next)
{
  constexpr int kDx[4] = {1, 0, -1, 0}, kDy[4] = {0, 1, 0, -1};
  if (actions.size() != pos.size() || next.size() != pos.size() || heading.size() != pos.size())
    return "rotation step: sizes of positions, headings, actions differ";
  for (size_t i = 0; i < pos.size(); ++i) {
    const char a = actions[i];
    planner::Vertex want = pos[i];
    if (a == 'F') {
      const int o = heading[i];
      want = g.at(g.cell_x(pos[i]) + kDx[o], g.cell_y(pos[i]) + kDy[o]);
      if (want < 0) return "agent " + std::to_string(i) + " moves forward into a wall at vertex " + std::to_string(pos[i]);
    } else if (a != 'R' && a != 'C' && a != 'W') {
      return "agent " + std::to_string(i) + ": unknown action '" + std::string(1, a) + "'";
    }
    if (next[i] != want)
      return "agent " + std::to_string(i) + ": action " + std::string(1, a) + " from vertex " + std::to_string(pos[i]) +
             " does not lead to vertex " + std::to_string(next[i]);
  }
  return "";
}

char turn_toward(int h, int d) { return ((d - h + 4) % 4) == 3 ? 'C' : 'R'; }

}  // namespace tasks
