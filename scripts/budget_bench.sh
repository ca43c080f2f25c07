#!/usr/bin/env bash
# Lifelong planning time vs the budget (issue 11): LoRR 2024 WAREHOUSE, the first AGENTS
# agents, STEPS steps, rtlacam, budgets 1 and 10 ms, grid4 and rotation. Runs BASE (a
# baseline binary, optional) and BIN in the same session, one after the other, and prints
# planner ms per step p50 / p99 / max, the set_goals share, the tables' precompute share,
# throughput and max RSS, with BIN / BASE ratios. Rows in $OUT/runs.jsonl, table in
# $OUT/table.md. Run from the repository root after building rtlacam-lifelong (Release).
# Per-step thread CPU time (plannerCpuTimeStats) is printed beside wall time where the
# binary records it: a loaded box preempts steps, which shows in wall time only. EXACT=1
# also runs BIN with --exact-queries (every distance query grows its table on the spot).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/apps/rtlacam-lifelong}
BASE=${BASE:-}
OUT=${OUT:-out/budget}
AGENTS=${AGENTS:-1000}
STEPS=${STEPS:-500}
BUDGETS=${BUDGETS:-"1 10"}
MODELS=${MODELS:-"grid4 rotation"}
P=${PROBLEM:-../shared/benchmarks/lorr/2024/warehouse.domain/WAREHOUSE.json}
mkdir -p "$OUT"
: > "$OUT/runs.jsonl"
for m in $MODELS; do
  for b in $BUDGETS; do
    for which in base new exact; do
      bin=$BIN; flags=""; [ $which = base ] && bin=$BASE
      [ $which = exact ] && { [ -n "${EXACT:-}" ] || continue; flags=--exact-queries; }
      [ -z "$bin" ] && continue
      /usr/bin/time -f '%M' -o "$OUT/rss.txt" "$bin" --problem "$P" --agents "$AGENTS" --steps "$STEPS" \
        --budget-ms "$b" --action-model "$m" --seed 0 --quiet $flags > "$OUT/one.json"
      python3 - "$OUT" "$which" "$m" "$b" <<'PY'
import json, sys
out, which, m, b = sys.argv[1:]
j = json.load(open(f"{out}/one.json"))
j.update(which=which, model=m, budget=float(b), maxRssKB=int(open(f"{out}/rss.txt").read().split()[-1]))
open(f"{out}/runs.jsonl", "a").write(json.dumps(j) + "\n")
PY
    done
  done
done
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
rows = [json.loads(l) for l in open(f"{out}/runs.jsonl")]
lines = ["| model | budget ms | build | wall p50 / p99 / max ms | CPU p50 / p99 / max ms | set_goals p99 / max ms (CPU p99) | precompute p99 / max ms | steps over budget wall / CPU | tasks/step | max RSS MB | p99 ratio new/base |",
         "|---|---:|---|---|---|---|---|---:|---:|---:|---:|"]
for r in rows:
    s, e = r["plannerTimeStats"], r["epochStartStats"]
    c = r.get("plannerCpuTimeStats")
    cpu = f"{c['p50']:.2f} / {c['p99']:.2f} / {c['max']:.2f}" if c else "-"
    ec = r.get("epochStartCpuStats")
    ecpu = f" ({ec['p99']:.2f})" if ec else ""
    pc = r.get("precomputeStats", {"p99": 0, "max": 0})
    base = [q for q in rows if q["which"] == "base" and q["model"] == r["model"] and q["budget"] == r["budget"]]
    ratio = f"{s['p99'] / base[0]['plannerTimeStats']['p99']:.2f}" if r["which"] != "base" and base else "-"
    over = f"{r.get('stepsOverBudget', '-')} / {r.get('stepsOverBudgetCpu', '-')}"
    lines.append(f"| {r['model']} | {r['budget']:g} | {r['which']} | {s['p50']:.2f} / {s['p99']:.2f} / {s['max']:.2f} | {cpu} | "
                 f"{e['p99']:.2f} / {e['max']:.2f}{ecpu} | {pc['p99']:.2f} / {pc['max']:.2f} | {over} | {r['taskThroughput']:.3f} | {r['maxRssKB'] // 1024} | {ratio} |")
open(f"{out}/table.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
