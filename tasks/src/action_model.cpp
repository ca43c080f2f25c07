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

char grid4_letter(const planner::Graph& g, planner::Vertex u, planner::Vertex v)
{
  if (u == v) return 'W';
  constexpr char kLetter[4] = {'R', 'U', 'L', 'D'};  // PlanViz: U = row + 1 (south)
  return kLetter[heading_of_move(g, u, v)];
}

std::string check_rotation_step(const planner::Graph& g, const planner::Config& pos, const std::vector<int>& heading,
                                const std::string& actions, const planner::Config& next)
{
  if (actions.size() != pos.size() || next.size() != pos.size() || heading.size() != pos.size())
    return "rotation step: sizes of positions, headings, actions differ";
  for (size_t i = 0; i < pos.size(); ++i) {
    const char a = actions[i];
    const planner::Vertex want = planner::result_state(g, {pos[i], heading[i]}, a).v;
    if (a == 'F') {
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

}  // namespace tasks
