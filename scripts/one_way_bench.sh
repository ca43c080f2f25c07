#!/usr/bin/env bash
# One-way aisles against two-way aisles (issue 24), each pair in the same run:
#  1. fraction solved by RT-LaCAM at 1 ms per iteration on warehouse-10-20-10-2-1, two-way
#     (the map as it is) and one-way (rtlacam-bench --one-way-aisles: aisles between shelf
#     rows alternately east and west, planner/one_way_aisles.hpp); same scenarios, N, seeds;
#  2. lifelong throughput (errands per tick) on the small SUMO warehouse with two-way and
#     one-way picking aisles (config/small_warehouse_lifelong.yaml, small_oneway_lifelong.yaml).
# Prints a table per part and the one-way/two-way ratios. Run from the repository root after
# a Release build into build/ (BUILD=... otherwise). Knobs: SCENS, AGENTS, SEEDS, MAX_STEPS,
# TIMEOUT_S, TICKS (lifelong ticks), SKIP_SUMO=1.
# A run is solved when the agents reach their goals within MAX_STEPS iterations (5000: 5 s of
# 1 ms iterations); TIMEOUT_S (planning time) is only a safety net. A planning-time cap alone
# does not compare like for like: once RT-LaCAM*'s refinement has ended its iterations cost
# almost nothing, so a run that follows a 58660-step first path counted as solved, while with
# the lookahead search (rt_lacam.hpp) every iteration spends its millisecond (session 42).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
MAPS=${MAPS:-../shared/benchmarks/movingai}
SCENS=${SCENS:-"1 2 3 4 5"}
AGENTS=${AGENTS:-"200 400 600 800"}
SEEDS=${SEEDS:-"0"}
MAX_STEPS=${MAX_STEPS:-5000}
TIMEOUT_S=${TIMEOUT_S:-120}
TICKS=${TICKS:-1000}
OUT=${OUT:-out/one_way_bench}
mkdir -p "$OUT"
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

echo "## RT-LaCAM, 1 ms per iteration, warehouse-10-20-10-2-1 (solved within ${MAX_STEPS} iterations; safety net ${TIMEOUT_S} s of planning)"
echo "| N | runs | solved two-way | solved one-way | ratio one/two | mean makespan two-way | mean makespan one-way |"
echo "|---|---|---|---|---|---|---|"
for n in $AGENTS; do
  runs=0 s2=0 s1=0 st2=0 st1=0
  for sc in $SCENS; do
    for seed in $SEEDS; do
      for mode in two one; do
        flag=""; [ "$mode" = one ] && flag="--one-way-aisles"
        out="$OUT/wh_${mode}_n${n}_s${sc}_seed${seed}.json"
        "$BUILD/apps/rtlacam-bench" --map "$MAPS/warehouse-10-20-10-2-1.map" \
          --scen "$MAPS/warehouse-10-20-10-2-1-random-$sc.scen" -N "$n" --solver rtlacam --cutoff-ms 1 \
          --max-steps "$MAX_STEPS" --timeout-s "$TIMEOUT_S" --seed "$seed" --json $flag > "$out" || true
        read -r solved steps < <(python3 -c "import json,sys; j=json.load(open('$out')); print(int(bool(j['solved'])), j.get('makespan', 0))")
        if [ "$mode" = two ]; then s2=$((s2 + solved)); st2=$((st2 + steps)); else s1=$((s1 + solved)); st1=$((st1 + steps)); fi
      done
      runs=$((runs + 1))
    done
  done
  python3 -c "
r,s2,s1,t2,t1=$runs,$s2,$s1,$st2,$st1
f2,f1=s2/r,s1/r
print(f'| $n | {r} | {f2:.2f} | {f1:.2f} | ' + (f'{f1/f2:.2f}' if f2 else 'n/a') + f' | {t2/r:.0f} | {t1/r:.0f} |')"
done

[ "${SKIP_SUMO:-0}" = 1 ] && exit 0
echo
echo "## Lifelong, small SUMO warehouse, 16 AGVs, RT-LaCAM 1 ms, ${TICKS} ticks"
echo "| aisles | tasks | errands | ticks | errands/tick | ratio one/two | collisions | jumps | violations | error |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for mode in two one; do
  cfg=config/small_warehouse_lifelong.yaml; [ "$mode" = one ] && cfg=config/small_oneway_lifelong.yaml
  dir="$OUT/lifelong_$mode"
  "$BUILD/apps/rtlacam-sumo" "$cfg" --out "$dir" --max-ticks "$TICKS" > "$dir.log" 2>&1 || true
done
python3 - "$OUT/lifelong_two/metrics.json" "$OUT/lifelong_one/metrics.json" <<'EOF'
import json, sys
base = None
for mode, path in (("two", sys.argv[1]), ("one", sys.argv[2])):
    m = json.load(open(path))
    l = m["lifelong"]
    rate = l["errandThroughput"]
    base = rate if base is None else base
    ratio = f"{rate / base:.2f}" if base else "n/a"
    print(f"| {mode}-way | {l['numTaskFinished']} | {l['numErrandFinished']} | {m['ticks']} | {rate:.3f} | {ratio} | "
          f"{m['collisions']} | {m['commands']['jumps']} | {m['violations']} | {m['error'] or '-'} |")
EOF
