#include "controller/fleet_view.hpp"


namespace controller {

AgvState agv_state(bool stuck, bool delayed, bool waiting, bool moving, bool carrying)
{
  if (stuck) return AgvState::Stuck;
  if (delayed) return AgvState::Delayed;
  if (waiting) return AgvState::Waiting;
  if (moving) return carrying ? AgvState::Carrying : AgvState::Moving;
  return AgvState::Idle;
}

// Told apart at a glance and by colour-blind eyes (blue/orange/grey carry the main split);
// none is SUMO's default vehicle yellow, so an AGV never coloured stands out.
Rgb state_colour(AgvState s)
{
  switch (s) {
    case AgvState::Idle: return {150, 150, 150};     // grey
    case AgvState::Moving: return {30, 170, 60};     // green
    case AgvState::Carrying: return {30, 100, 230};  // blue
    case AgvState::Waiting: return {255, 150, 0};    // orange
    case AgvState::Delayed: return {170, 60, 200};   // purple
    case AgvState::Stuck: return {220, 20, 30};      // red
  }
  return {0, 0, 0};
}

const char* state_name(AgvState s)
{
  switch (s) {
    case AgvState::Idle: return "idle";
    case AgvState::Moving: return "moving";
    case AgvState::Carrying: return "carrying";
    case AgvState::Waiting: return "waiting";
    case AgvState::Delayed: return "delayed";
    case AgvState::Stuck: return "stuck";
  }
  return "?";
}

Rgb goal_colour() { return {0, 190, 200}; }  // cyan: no AGV state uses it

FleetView::FleetView(SumoBackend& sumo, const gridify::CellMap& map, std::vector<std::string> ids, double marker_m)
    : sumo_(sumo), map_(map), ids_(std::move(ids)), marker_(marker_m), shown_(ids_.size(), -1)
{
}

void FleetView::show(const std::vector<AgvState>& states)
{
  for (size_t i = 0; i < ids_.size(); ++i) {
    const int s = static_cast<int>(states[i]);
    if (shown_[i] == s) continue;
    const Rgb c = state_colour(states[i]);
    sumo_.set_color(ids_[i], c.r, c.g, c.b, 255);
    shown_[i] = s;
    ++st_.colour_calls;
  }
}

void FleetView::goals(const planner::Config& goals)
{
  const bool first = goal_.empty();
  if (first) goal_.assign(ids_.size(), -1);
  const Rgb c = goal_colour();
  for (size_t i = 0; i < ids_.size(); ++i) {
    if (goal_[i] == goals[i]) continue;
    const gridify::Cell& cell = map_.cells[goals[i]];
    // An outline (a POI is a disc of fixed size in sumo-gui 1.15, whatever its width), under
    // the AGVs, so an AGV on its goal stays visible; its type is the AGV's id.
    const double h = marker_ / 2;
    const SumoBackend::Shape square{{cell.x - h, cell.y - h}, {cell.x + h, cell.y - h}, {cell.x + h, cell.y + h},
                                    {cell.x - h, cell.y + h}, {cell.x - h, cell.y - h}};
    if (goal_[i] < 0)
      sumo_.add_polygon(goal_id(ids_[i]), ids_[i], square, c.r, c.g, c.b, marker_ / 6);
    else
      sumo_.set_polygon_shape(goal_id(ids_[i]), square);
    goal_[i] = goals[i];
    ++st_.goal_calls;
  }
}

}  // namespace controller
