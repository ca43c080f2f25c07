#pragma once
// The floor a priority hint (RealtimePlanner::set_priority_hint, the task layer's urgency)
// puts under an agent's PIBT priority at an epoch start: tie + round(hint), `tie` the
// priority's tie part (its initial fraction, dist/N or the like). Whole numbers keep the tie
// part, so the agent falls back to it when it reaches its goal, as PIBT's own elapsed time
// does; a priority above the floor stays. One formula for the LaCAM family (float priorities,
// lacam/priority.hpp) and pibt-rot (double, rotation/rotation_pibt.cpp).
#include <algorithm>
#include <cmath>

namespace planner {

template <class P>
inline P hint_floor(P prio, P tie, float hint)
{
  return hint > 0 ? std::max(prio, tie + static_cast<P>(std::round(hint))) : prio;
}

}  // namespace planner
