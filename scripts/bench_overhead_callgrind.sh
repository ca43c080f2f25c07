#!/usr/bin/env bash
# RT-LaCAM's overhead over full-horizon LaCAM in instructions (valgrind callgrind), which
# stay repeatable on a loaded machine where wall-clock ratios do not. Same instance, same
# seed: both build the identical search tree, so the difference is RT-LaCAM's per-iteration
# work (walking to the root, rerooting, budget checks). A "none" run (PIBT, 0 steps) gives
# the cost of loading the map and scenario, subtracted from both. RT-LaCAM runs with
# --no-refine (to the goal = to the first solution); the last column is what refinement
# adds before the first solution (recording neighbour links): LaCAM --refine stopped at its
# first solution over LaCAM --no-refine.
#   scripts/bench_overhead_callgrind.sh [bench-binary]
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build/apps/rtlacam-bench}
D=data/movingai
ir() {  # total instructions of one run
  local f; f=$(mktemp)
  valgrind --tool=callgrind --callgrind-out-file="$f" "$BIN" "$@" --json >/dev/null 2>&1
  awk '/^summary:/ {print $2}' "$f"; rm -f "$f"
}
printf '| instance | LaCAM Mi | %s |\n' "rt@0.01 | rt@0.1 | rt@1 | rt@10 | rt@100 | links"
printf '|---|---|---|---|---|---|---|---|\n'
for spec in "random-32-32-20 400" "room-32-32-4 150" "warehouse-10-20-10-2-1 400" "warehouse-10-20-10-2-1 600"; do
  set -- $spec; m=$1; n=$2
  args=(--map $D/$m.map --scen $D/$m-random-1.scen -N $n)
  base=$(ir "${args[@]}" --solver pibt --max-steps 0)
  lacam=$(( $(ir "${args[@]}" --solver lacam --no-refine) - base ))
  links=$(( $(ir "${args[@]}" --solver lacam --refine) - base ))
  row="| $m N=$n | $((lacam / 1000000)) |"
  for c in 0.01 0.1 1 10 100; do
    rt=$(( $(ir "${args[@]}" --solver rtlacam --no-refine --cutoff-ms $c) - base ))
    row="$row $(awk -v a=$rt -v b=$lacam 'BEGIN{printf "%.3f", a/b}') |"
  done
  row="$row $(awk -v a=$links -v b=$lacam 'BEGIN{printf "%.3f", a/b}') |"
  echo "$row"
done
