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

char turn_toward(int h, int d) { return ((d - h + 4) % 4) == 3 ? 'C' : 'R'; }

}  // namespace tasks
