#!/usr/bin/env bash
# The rotation-native planner (--solver pibt-rot) against the best cell-plan rotation
# setting (rtlacam --no-refine, turn-aware PIBT order, RotationExecutor), in one session:
#  1. LoRR 2023 MR23-I-03/04/05/07/08 (roundrobin), SEEDS seeds, BUDGET ms: errands/step vs
#     the LoRR best (scripts/rotation_bench.sh; tables in $OUT/{pibt-rot,base}/table.md);
#  2. LoRR 2024 RANDOM-01..05 (pool, greedy), seed 0: tasks/step (the start kit's default
#     planner can run the same files: docs/rotation_lorr.md).
# Both print planner ms per step p50 / p99 / max. Run from the repository root after
# building rtlacam-lifelong (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/apps/rtlacam-lifelong}
OUT=${OUT:-out/rotation-native}
SEEDS=${SEEDS:-"0 1 2 3 4"}
BUDGET=${BUDGET:-100}
mkdir -p "$OUT"
uptime
BIN=$BIN OUT=$OUT/pibt-rot MODELS=rotation SEEDS="$SEEDS" BUDGET=$BUDGET EXTRA="--solver pibt-rot" scripts/rotation_bench.sh
BIN=$BIN OUT=$OUT/base MODELS=rotation SEEDS="$SEEDS" BUDGET=$BUDGET EXTRA="--no-refine" scripts/rotation_bench.sh
uptime
python3 - "$OUT" <<'PY'
import json, statistics, sys
out = sys.argv[1]
print("| instance | solver | planner ms p50 / p99 / max (median over seeds of p50, max of p99 and max) |")
print("|---|---|---|")
for s in ("pibt-rot", "base"):
    rows = [json.loads(l) for l in open(f"{out}/{s}/runs.jsonl")]
    for inst in ("MR23-I-04", "MR23-I-03", "MR23-I-05", "MR23-I-07", "MR23-I-08"):
        rs = [r["plannerTimeStats"] for r in rows if r["instance"] == inst]
        print(f"| {inst} | {s} | {statistics.median(r['p50'] for r in rs):.3f} / {max(r['p99'] for r in rs):.2f} / {max(r['max'] for r in rs):.2f} |")
PY
L=../shared/benchmarks/lorr/2024/random.domain
echo "| instance | agents | steps | solver | tasks/step | errands/step | planner ms p50 / p99 / max | errors |"
echo "|---|---:|---:|---|---:|---:|---|---:|"
for i in 01 02 03 04 05; do
  for s in pibt-rot "rtlacam --no-refine"; do
    "$BIN" --problem $L/RANDOM-$i.json --action-model rotation --budget-ms $BUDGET --seed 0 --quiet --solver $s |
      python3 -c "import json,sys; j=json.load(sys.stdin); t=j['plannerTimeStats']; print(f\"| RANDOM-$i | {j['teamSize']} | {j['makespan']} | $s | {j['taskThroughput']:.3f} | {j['errandThroughput']:.3f} | {t['p50']:.3f} / {t['p99']:.2f} / {t['max']:.2f} | {j['numPlannerErrors']} |\")"
  done
done
uptime
