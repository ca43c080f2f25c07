#!/usr/bin/env bash
# EPIBT (--solver epibt) against pibt-rot in one session, rotation model (LoRR MAPF_T):
#  1. LoRR 2023 MR23-I-04/03/05/07/08 (roundrobin), SEEDS seeds: errands/step, ratio to
#     pibt-rot (the first variant) and to the LoRR best, planner ms p50 / p99 / max;
#  2. (PART2=1) LoRR 2024 RANDOM-01..05 (pool, greedy), seed 0: tasks/step.
# VARIANTS: ';'-separated "name=rtlacam-lifelong options" (the first is the baseline).
# Neither planner's decisions depend on timing unless epibt hits its deadline (never at
# 100 ms here): numbers reproduce at any load; the times do not. Run from the repository
# root after building rtlacam-lifelong (Release). Tables in $OUT/table.md.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/apps/rtlacam-lifelong}
OUT=${OUT:-out/epibt}
SEEDS=${SEEDS:-"0 1 2 3 4"}
BUDGET=${BUDGET:-100}
INSTANCES=${INSTANCES:-"04 03 05 07 08"}
VARIANTS=${VARIANTS:-"pibt-rot=--solver pibt-rot;epibt=--solver epibt"}
PART2=${PART2:-0}
L=../shared/benchmarks/lorr/2023/random.domain
mkdir -p "$OUT"
: > "$OUT/runs.jsonl"
uptime
IFS=';' read -ra VS <<< "$VARIANTS"
for i in $INSTANCES; do
  for v in "${VS[@]}"; do
    name=${v%%=*}
    opts=${v#*=}
    for s in $SEEDS; do
      # shellcheck disable=SC2086
      "$BIN" --problem $L/MR23-I-$i.json --action-model rotation --budget-ms $BUDGET --seed $s --quiet $opts \
        | python3 -c "import json,sys; j=json.load(sys.stdin); j['instance']='MR23-I-$i'; j['variant']='$name'; print(json.dumps(j))" >> "$OUT/runs.jsonl"
    done
  done
done
uptime
python3 - "$OUT" <<'PY'
import json, statistics, sys
out = sys.argv[1]
best = {"MR23-I-04": 3.48, "MR23-I-03": 6.08, "MR23-I-05": 7.43, "MR23-I-07": 5.91, "MR23-I-08": 3.03}
rows = [json.loads(l) for l in open(f"{out}/runs.jsonl")]
variants = list(dict.fromkeys(r["variant"] for r in rows))
lines = ["| instance | agents | variant | seeds | errands/step mean (min-max) | / " + variants[0] + " | LoRR best | / best | planner ms p50 / p99 / max | CPU p99 | errors |",
         "|---|---:|---|---:|---|---:|---:|---:|---|---:|---:|"]
for inst in best:
    base = [r["errandThroughput"] for r in rows if r["instance"] == inst and r["variant"] == variants[0]]
    for v in variants:
        rs = [r for r in rows if r["instance"] == inst and r["variant"] == v]
        if not rs:
            continue
        x = [r["errandThroughput"] for r in rs]
        m = statistics.mean(x)
        t = [r["plannerTimeStats"] for r in rs]
        cpu = max(r.get("plannerCpuTimeStats", {}).get("p99", float("nan")) for r in rs)
        lines.append(f"| {inst} | {rs[0]['teamSize']} | {v} | {len(rs)} | {m:.2f} ({min(x):.2f}-{max(x):.2f}) | "
                     f"{m / statistics.mean(base):.2f} | {best[inst]} | {m / best[inst]:.2f} | "
                     f"{statistics.median(a['p50'] for a in t):.3f} / {max(a['p99'] for a in t):.2f} / {max(a['max'] for a in t):.2f} | "
                     f"{cpu:.2f} | {sum(r['numPlannerErrors'] for r in rs)} |")
open(f"{out}/table.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
if [ "$PART2" = 1 ]; then
  L=../shared/benchmarks/lorr/2024/random.domain
  echo "| instance | agents | steps | variant | tasks/step | errands/step | planner ms p50 / p99 / max | errors |" | tee -a "$OUT/table.md"
  echo "|---|---:|---:|---|---:|---:|---|---:|" | tee -a "$OUT/table.md"
  for i in 01 02 03 04 05; do
    for v in "${VS[@]}"; do
      name=${v%%=*}
      opts=${v#*=}
      # shellcheck disable=SC2086
      "$BIN" --problem $L/RANDOM-$i.json --action-model rotation --budget-ms $BUDGET --seed 0 --quiet $opts |
        python3 -c "import json,sys; j=json.load(sys.stdin); t=j['plannerTimeStats']; print(f\"| RANDOM-$i | {j['teamSize']} | {j['makespan']} | $name | {j['taskThroughput']:.3f} | {j['errandThroughput']:.3f} | {t['p50']:.3f} / {t['p99']:.2f} / {t['max']:.2f} | {j['numPlannerErrors']} |\")" | tee -a "$OUT/table.md"
    done
  done
  uptime
fi
