#!/usr/bin/env bash
# RT-LaCAM*'s lookahead on one-way aisles (rt_lacam.hpp, "Lookahead"; docs/rt_lacam_star.md
# "Session 42"): warehouse-10-20-10-2-1 with alternate one-way aisles (rtlacam-bench
# --one-way-aisles), lookahead on (the default) against --no-lookahead, the same binary, each
# pair back to back; every plan checked by rtlacam-bench's validator. Prints per cell the
# makespan, standard SOC / LB, SOC on / off and iteration CPU p99 / max, then geometric means.
# Knobs: BUILD (build), MAPS (../shared/benchmarks/movingai), NS ("100 200 300 400"),
# SCENS ("1 2 3 4 5"), CUTOFF_MS (1; empty with EXPANSIONS=50 for deterministic runs),
# TIMEOUT_S (20).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
MAPS=${MAPS:-../shared/benchmarks/movingai}
NS=${NS:-"100 200 300 400"}
SCENS=${SCENS:-"1 2 3 4 5"}
CUTOFF_MS=${CUTOFF_MS-1}
EXPANSIONS=${EXPANSIONS:-}
TIMEOUT_S=${TIMEOUT_S:-20}
budget=()
[ -n "$CUTOFF_MS" ] && budget+=(--cutoff-ms "$CUTOFF_MS")
[ -n "$EXPANSIONS" ] && budget+=(--budget-expansions "$EXPANSIONS")
rows=$(mktemp)
for n in $NS; do for sc in $SCENS; do for v in off on; do
  flag=(); [ "$v" = off ] && flag=(--no-lookahead)
  "$BUILD/apps/rtlacam-bench" --map "$MAPS/warehouse-10-20-10-2-1.map" \
    --scen "$MAPS/warehouse-10-20-10-2-1-random-$sc.scen" -N "$n" --solver rtlacam "${budget[@]}" \
    --timeout-s "$TIMEOUT_S" --one-way-aisles "${flag[@]}" --json 2>/dev/null |
    python3 -c "import json,sys; j=json.load(sys.stdin); print('$v', $n, $sc, int(j['solved']), int(j['valid']), j['makespan'], j['soc'], j['soc_lb'], j['p99_iteration_cpu_ms'], j['max_iteration_cpu_ms'])" >> "$rows"
done; done; done
echo "## one-way warehouse-10-20-10-2-1, budget: ${budget[*]}; lookahead off -> on"
python3 - "$rows" <<'PY'
import collections, math, sys
rows = collections.defaultdict(dict)
for line in open(sys.argv[1]):
    v, n, sc, sol, val, mk, soc, lb, p99, mx = line.split()
    rows[(int(n), int(sc))][v] = (int(sol), int(val), int(mk), int(soc), int(lb), float(p99), float(mx))
print("| N | scen | solved off / on | makespan off -> on | SOC/LB off -> on | SOC on/off | p99 iteration CPU ms off / on | max off / on |")
print("|---|---|---|---|---|---|---|---|")
soc_r, mk_r, bad = [], [], 0
for (n, sc), d in sorted(rows.items()):
    a, b = d["off"], d["on"]
    bad += (not a[1]) + (not b[1])
    line = f"| {n} | {sc} | {a[0]} / {b[0]} | {a[2]} -> {b[2]} | "
    if a[0] and b[0]:
        soc_r.append(b[3] / a[3]); mk_r.append(b[2] / a[2])
        line += f"{a[3] / a[4]:.3f} -> {b[3] / b[4]:.3f} | {b[3] / a[3]:.3f} |"
    else:
        line += "- | - |"
    print(line + f" {a[5]:.3f} / {b[5]:.3f} | {a[6]:.2f} / {b[6]:.2f} |")
gm = lambda x: math.exp(sum(map(math.log, x)) / len(x)) if x else float("nan")
print(f"cells solved both ways: {len(soc_r)}; SOC on/off gm {gm(soc_r):.3f} (min {min(soc_r, default=0):.3f}, "
      f"max {max(soc_r, default=0):.3f}); makespan on/off gm {gm(mk_r):.3f}; invalid plans: {bad}")
PY
rm -f "$rows"
