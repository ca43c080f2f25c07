#!/usr/bin/env bash
# pibt-rot under a per-step budget (docs/rotation_lorr.md "Bounded rotation tables"): LoRR
# 2024 WAREHOUSE, the first AGENTS agents, STEPS steps, seed 0, budgets BUDGETS ms; BASE (a
# baseline binary, optional) and BIN with bounded queries (default), --exact-queries, and
# each guidance in GUIDANCE, alternating in one window. Prints wall and thread-CPU ms per
# step p50 / p99 / max, steps over the budget on CPU, tasks/step and max RSS. Rows in
# $OUT/runs.jsonl. Run from the repository root after building rtlacam-lifelong (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/apps/rtlacam-lifelong}
BASE=${BASE:-}
OUT=${OUT:-out/guidance-budget}
AGENTS=${AGENTS:-1000}
STEPS=${STEPS:-500}
BUDGETS=${BUDGETS:-"1 10"}
GUIDANCE=${GUIDANCE:-"none arrows:1,3,1"}
P=${PROBLEM:-../shared/benchmarks/lorr/2024/warehouse.domain/WAREHOUSE.json}
mkdir -p "$OUT"
: > "$OUT/runs.jsonl"
uptime
for b in $BUDGETS; do
  variants=()
  [ -n "$BASE" ] && variants+=("base|$BASE|")
  for gd in $GUIDANCE; do
    f="--guidance none"; case $gd in none) ;; arrows:*) f="--guidance arrows --guidance-costs ${gd#arrows:}" ;; *) f="--guidance $gd" ;; esac
    variants+=("$gd bounded|$BIN|$f" "$gd exact|$BIN|$f --exact-queries")
  done
  for v in "${variants[@]}"; do
    IFS='|' read -r name bin flags <<< "$v"
    /usr/bin/time -f '%M' -o "$OUT/rss.txt" "$bin" --problem "$P" --agents "$AGENTS" --steps "$STEPS" --budget-ms "$b" \
      --action-model rotation --solver pibt-rot --seed 0 --quiet $flags > "$OUT/one.json"
    python3 - "$OUT" "$name" "$b" <<'PY'
import json, sys
out, name, b = sys.argv[1:]
j = json.load(open(f"{out}/one.json"))
j.update(variant=name, budget=float(b), maxRssKB=int(open(f"{out}/rss.txt").read().split()[-1]))
open(f"{out}/runs.jsonl", "a").write(json.dumps(j) + "\n")
PY
  done
done
uptime
python3 - "$OUT" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(f"{sys.argv[1]}/runs.jsonl")]
print("| budget ms | variant | wall p50 / p99 / max ms | CPU p50 / p99 / max ms | steps over budget on CPU | tasks/step | errands/step | max RSS MB |")
print("|---:|---|---|---|---:|---:|---:|---:|")
for r in rows:
    w, c = r["plannerTimeStats"], r.get("plannerCpuTimeStats")
    cs = f"{c['p50']:.2f} / {c['p99']:.2f} / {c['max']:.2f}" if c else "-"
    print(f"| {r['budget']:g} | {r['variant']} | {w['p50']:.2f} / {w['p99']:.2f} / {w['max']:.2f} | {cs} | {r.get('stepsOverBudgetCpu', '-')} | "
          f"{r['taskThroughput']:.3f} | {r['errandThroughput']:.3f} | {r['maxRssKB'] // 1024} |")
PY
