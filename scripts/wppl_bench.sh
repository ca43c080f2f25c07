#!/usr/bin/env bash
# Windowed LNS (--solver wppl) against pibt-rot on LoRR 2023 MR23-I-04/03/05/07/08
# (roundrobin, rotation model), SEEDS seeds, BUDGET ms per step, one core each, the two
# solvers alternating per seed (same time window: wppl's LNS depends on time, pibt-rot does
# not). errands/step vs the LoRR best, planner ms p50 / p99 / max (wall and CPU). One JSON
# summary per run in $OUT/runs.jsonl, the table in $OUT/table.md, the load in $OUT/load.txt.
# Run from the repository root after building rtlacam-lifelong (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/apps/rtlacam-lifelong}
OUT=${OUT:-out/wppl}
SEEDS=${SEEDS:-"0 1 2 3 4"}
BUDGET=${BUDGET:-100}
INSTANCES=${INSTANCES:-"04 03 05 07 08"}
SOLVERS=${SOLVERS:-"pibt-rot wppl"}
EXTRA=${EXTRA:-}  # more options for wppl, e.g. "--wppl-window 10"
L=../shared/benchmarks/lorr/2023/random.domain
mkdir -p "$OUT"
: > "$OUT/runs.jsonl"
uptime > "$OUT/load.txt"
for i in $INSTANCES; do
  for s in $SEEDS; do
    for solver in $SOLVERS; do
      x=""; [ "$solver" = wppl ] && x="$EXTRA"
      nice "$BIN" --problem $L/MR23-I-$i.json --action-model rotation --solver $solver --budget-ms $BUDGET --seed $s --quiet $x \
        | python3 -c "import json,sys; j=json.load(sys.stdin); j['instance']='MR23-I-$i'; j['solver']='$solver'; print(json.dumps(j))" >> "$OUT/runs.jsonl"
    done
    uptime >> "$OUT/load.txt"
  done
done
python3 - "$OUT" <<'PY'
import json, statistics, sys
out = sys.argv[1]
best = {"MR23-I-04": 3.48, "MR23-I-03": 6.08, "MR23-I-05": 7.43, "MR23-I-07": 5.91, "MR23-I-08": 3.03}
rows = [json.loads(l) for l in open(f"{out}/runs.jsonl")]
lines = ["| instance | agents | steps | solver | seeds | errands/step mean (min-max) | / pibt-rot | / LoRR best | wall ms p50 / p99 / max | CPU ms p50 / p99 / max | errors |",
         "|---|---:|---:|---|---:|---|---:|---:|---|---|---:|"]
for inst in best:
    base = [r["errandThroughput"] for r in rows if r["instance"] == inst and r["solver"] == "pibt-rot"]
    for solver in dict.fromkeys(r["solver"] for r in rows):
        rs = [r for r in rows if r["instance"] == inst and r["solver"] == solver]
        if not rs:
            continue
        x = [r["errandThroughput"] for r in rs]
        mean = statistics.mean(x)
        rel = f"{mean / statistics.mean(base):.2f}" if base else "-"
        w = [r["plannerTimeStats"] for r in rs]
        c = [r.get("plannerCpuTimeStats", r["plannerTimeStats"]) for r in rs]
        f = lambda t: f"{statistics.median(a['p50'] for a in t):.2f} / {max(a['p99'] for a in t):.1f} / {max(a['max'] for a in t):.1f}"
        lines.append(f"| {inst} | {rs[0]['teamSize']} | {rs[0]['makespan']} | {solver} | {len(rs)} | "
                     f"{mean:.2f} ({min(x):.2f}-{max(x):.2f}) | {rel} | {mean / best[inst]:.2f} | {f(w)} | {f(c)} | "
                     f"{sum(r['numPlannerErrors'] for r in rs)} |")
open(f"{out}/table.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
