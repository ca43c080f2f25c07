#!/usr/bin/env bash
# LoRR 2023 random-32-32-20 (MR23-I-03/04/05/07/08, roundrobin) with the rotation action
# model (LoRR MAPF_T) beside grid4, rtlacam, SEEDS seeds, BUDGET ms per step; errands/step
# vs the LoRR best. One JSON summary per run in $OUT/runs.jsonl, the table in $OUT/table.md.
# Run from the repository root after building rtlacam-lifelong (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/apps/rtlacam-lifelong}
OUT=${OUT:-out/rotation}
SEEDS=${SEEDS:-"0 1 2 3 4"}
BUDGET=${BUDGET:-100}
MODELS=${MODELS:-"grid4 rotation"}
EXTRA=${EXTRA:-}  # more rtlacam-lifelong options, e.g. "--heading-cost ties"
L=../shared/benchmarks/lorr/2023/random.domain
mkdir -p "$OUT"
: > "$OUT/runs.jsonl"
for i in 04 03 05 07 08; do
  for m in $MODELS; do
    for s in $SEEDS; do
      "$BIN" --problem $L/MR23-I-$i.json --action-model $m --budget-ms $BUDGET --seed $s --quiet $EXTRA \
        | python3 -c "import json,sys; j=json.load(sys.stdin); j['instance']='MR23-I-$i'; print(json.dumps(j))" >> "$OUT/runs.jsonl"
    done
  done
done
python3 - "$OUT" <<'PY'
import json, statistics, sys
out = sys.argv[1]
best = {"MR23-I-04": 3.48, "MR23-I-03": 6.08, "MR23-I-05": 7.43, "MR23-I-07": 5.91, "MR23-I-08": 3.03}
rows = [json.loads(l) for l in open(f"{out}/runs.jsonl")]
lines = ["| instance | agents | steps | model | seeds | errands/step mean (min-max) | LoRR best | ratio | planner p99 / max ms (worst seed) | errors |",
         "|---|---:|---:|---|---:|---|---:|---:|---|---:|"]
for inst in best:
    for m in ("MAPF", "MAPF_T"):
        rs = [r for r in rows if r["instance"] == inst and r["actionModel"] == m]
        if not rs:
            continue
        x = [r["errandThroughput"] for r in rs]
        mean = statistics.mean(x)
        lines.append(f"| {inst} | {rs[0]['teamSize']} | {rs[0]['makespan']} | {'rotation' if m == 'MAPF_T' else 'grid4'} | {len(rs)} | "
                     f"{mean:.2f} ({min(x):.2f}-{max(x):.2f}) | {best[inst]} | {mean / best[inst]:.2f} | "
                     f"{max(r['plannerTimeStats']['p99'] for r in rs):.1f} / {max(r['plannerTimeStats']['max'] for r in rs):.1f} | "
                     f"{sum(r['numPlannerErrors'] for r in rs)} |")
open(f"{out}/table.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
