#include "planner/lacam/objective.hpp"

#include <stdexcept>

namespace planner {

Objective parse_objective(const std::string& s)
{
  if (s == "soc") return Objective::soc;
  if (s == "loss") return Objective::loss;
  throw std::invalid_argument("unknown objective '" + s + "' (soc | loss)");
}

const char* objective_name(Objective o) { return o == Objective::soc ? "soc" : "loss"; }

}  // namespace planner
