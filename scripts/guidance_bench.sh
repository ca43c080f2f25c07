#!/usr/bin/env bash
# pibt-rot with and without guidance (planner/guidance.hpp; docs/rotation_lorr.md "Guidance
# graph"): LoRR 2023 MR23-I-04/03/05/07/08 (roundrobin), SEEDS seeds, and LoRR 2024
# RANDOM-01..05 (pool, greedy) seed 0, one row per guidance setting in SETTINGS
# ("none", "arrows:ALONG,AGAINST,TURN" or a guidance FILE). pibt-rot decides without the
# clock, so errands/step do not depend on the load. Rows in $OUT/runs.jsonl, table on
# stdout. Run from the repository root after building rtlacam-lifelong (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/apps/rtlacam-lifelong}
OUT=${OUT:-out/guidance}
SEEDS=${SEEDS:-"0 1 2 3 4"}
SETTINGS=${SETTINGS:-"none arrows:2,6,2 arrows:1,2,1"}
RANDOM24=${RANDOM24:-1}
mkdir -p "$OUT"
: > "$OUT/runs.jsonl"
uptime
run() {  # problem setting seed instance
  local flags="--guidance none"
  case $2 in none) ;; arrows:*) flags="--guidance arrows --guidance-costs ${2#arrows:}" ;; *) flags="--guidance $2" ;; esac
  "$BIN" --problem "$1" --action-model rotation --budget-ms 100 --seed "$3" --quiet --solver pibt-rot $flags |
    python3 -c "import json,sys; j=json.load(sys.stdin); j['instance']='$4'; j['setting']='$2'; print(json.dumps(j))" >> "$OUT/runs.jsonl"
}
L=../shared/benchmarks/lorr/2023/random.domain
for i in 04 03 05 07 08; do
  for st in $SETTINGS; do
    for s in $SEEDS; do run $L/MR23-I-$i.json "$st" "$s" MR23-I-$i; done
  done
done
if [ "$RANDOM24" = 1 ]; then
  for i in 01 02 03 04 05; do
    for st in $SETTINGS; do run ../shared/benchmarks/lorr/2024/random.domain/RANDOM-$i.json "$st" 0 RANDOM-$i; done
  done
fi
uptime
python3 - "$OUT" "$SETTINGS" <<'PY'
import json, statistics, sys
out, settings = sys.argv[1], sys.argv[2].split()
best = {"MR23-I-04": 3.48, "MR23-I-03": 6.08, "MR23-I-05": 7.43, "MR23-I-07": 5.91, "MR23-I-08": 3.03}
rows = [json.loads(l) for l in open(f"{out}/runs.jsonl")]
print("| instance | agents | guidance | seeds | errands/step mean (min-max) | vs none | LoRR best ratio | tasks/step | planner ms p50 / p99 (worst seed) | errors |")
print("|---|---:|---|---:|---|---:|---:|---:|---|---:|")
for inst in sorted({r["instance"] for r in rows}, key=lambda x: (x[:4], list(best).index(x) if x in best else x)):
    base = None
    for st in settings:
        rs = [r for r in rows if r["instance"] == inst and r["setting"] == st]
        if not rs:
            continue
        x = [r["errandThroughput"] for r in rs]
        m = statistics.mean(x)
        base = m if base is None else base
        b = f"{m / best[inst]:.2f}" if inst in best else "-"
        print(f"| {inst} | {rs[0]['teamSize']} | {st} | {len(rs)} | {m:.3f} ({min(x):.2f}-{max(x):.2f}) | {m / base:.3f} | {b} | "
              f"{statistics.mean(r['taskThroughput'] for r in rs):.3f} | {statistics.median(r['plannerTimeStats']['p50'] for r in rs):.3f} / "
              f"{max(r['plannerTimeStats']['p99'] for r in rs):.2f} | {sum(r['numPlannerErrors'] for r in rs)} |")
PY
