#!/usr/bin/env bash
# The layering rules of docs/architecture.md, checked on the sources:
#   planner/ core includes neither family; planner/lacam and planner/rotation never include
#   each other; nothing in planner/ includes SUMO, YAML or another layer of ours.
# Usage: test_layers.sh SOURCE_DIR
set -uo pipefail
src=$1
fail=0
bad() { echo "test_layers: $1" >&2; fail=1; }
check() {  # check DESCRIPTION PATTERN FILES...
  local what=$1 pat=$2; shift 2
  local hits
  hits=$(grep -nE "$pat" "$@" 2>/dev/null)
  [[ -z "$hits" ]] || bad "$what:"$'\n'"$hits"
}
cd "$src/planner" || exit 1
factory="src/solver.cpp include/planner/solver.hpp src/rotation_settings.cpp include/planner/rotation_settings.hpp"
core=$(ls include/planner/*.hpp src/*.cpp | grep -vE '/(solver|rotation_settings)\.(cpp|hpp)$')
lacam=$(ls include/planner/lacam/*.hpp src/lacam/*.cpp)
rot=$(ls include/planner/rotation/*.hpp src/rotation/*.cpp)
[[ -n "$core" && -n "$lacam" && -n "$rot" ]] || { echo "test_layers: planner/ layout not found" >&2; exit 1; }
# solver and rotation_settings are the factory (library planner): they see both families.
check "planner core includes a family" '#include "planner/(lacam|rotation)/' $core
check "planner/lacam includes planner/rotation" '#include "planner/rotation/' $lacam
check "planner/rotation includes planner/lacam" '#include "planner/lacam/' $rot
check "planner/ includes another layer or SUMO" '#include [<"](libsumo|utils/traci|yaml-cpp|tasks/|executor/|controller/|gridify/|policy/)' $core $lacam $rot $factory
[[ $fail -eq 0 ]] && echo "test_layers: planner core / lacam / rotation layering holds"
exit $fail
