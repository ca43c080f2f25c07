#!/usr/bin/env bash
# Lifelong benchmark (issue 5 closing note): LoRR random-32-32-20 instances, 2023 round
# robin and 2024 pool (greedy; hungarian at 100 ms), solvers pibt / naive / rtlacam at
# 1, 10, 100 ms per step, pool runs with and without task reassignment; warehouse_large with the first 1,000 / 2,000 agents.
# Logs, tables and PNGs go to out/lifelong/ (OUT=...). Run from the repository root after
#   cmake -S . -B build-tasks -DCMAKE_BUILD_TYPE=Release && cmake --build build-tasks -j2
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build-tasks/apps/rtlacam-lifelong}
OUT=${OUT:-out/lifelong}
PY=${PYTHON:-/usr/bin/python3}
L=../shared/benchmarks/lorr
BUDGETS=${BUDGETS:-"1 10 100"}
SKIP_WAREHOUSE=${SKIP_WAREHOUSE:-0}

$PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/2023" --budget-ms $BUDGETS \
  --title "LoRR 2023 random-32-32-20, roundrobin" \
  --problems $L/2023/random.domain/MR23-I-04.json $L/2023/random.domain/MR23-I-03.json \
             $L/2023/random.domain/MR23-I-05.json $L/2023/random.domain/MR23-I-07.json $L/2023/random.domain/MR23-I-08.json
$PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/2024-greedy" --budget-ms $BUDGETS --assigner greedy \
  --title "LoRR 2024 random-32-32-20, pool/greedy" \
  --problems $L/2024/random.domain/RANDOM-0{1,2,3,4,5}.json
$PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/2024-hungarian" --budget-ms 100 --assigner hungarian \
  --title "LoRR 2024 random-32-32-20, pool/hungarian" \
  --problems $L/2024/random.domain/RANDOM-0{1,2,3,4,5}.json
# Task reassignment (--reassign) beside the default (assignments kept) in the same run.
$PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/2024-greedy-reassign" --budget-ms $BUDGETS --assigner greedy --reassign \
  --title "LoRR 2024 random-32-32-20, pool/greedy, reassignment" \
  --problems $L/2024/random.domain/RANDOM-0{1,2,3,4,5}.json
$PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/2024-hungarian-reassign" --budget-ms 100 --assigner hungarian --reassign \
  --title "LoRR 2024 random-32-32-20, pool/hungarian, reassignment" \
  --problems $L/2024/random.domain/RANDOM-0{1,2,3,4,5}.json
for a in greedy hungarian; do
  $PY scripts/compare_reassign.py "$OUT/2024-$a-reassign/results.json" "$OUT/2024-$a/results.json" --png "$OUT/2024-$a-reassign.png" | tee "$OUT/2024-$a-reassign.md"
done
$PY scripts/plot_lifelong.py -o "$OUT/MR23-I-05_completions.png" "$OUT"/2023/MR23-I-05_{pibt,naive,rtlacam}_100ms.json

if [ "$SKIP_WAREHOUSE" != 1 ]; then
  $PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/warehouse-1000" --budget-ms 100 --agents 1000 --steps 500 \
    --title "warehouse_large (MR23-I-10), first 1,000 agents" --problems $L/2023/warehouse.domain/MR23-I-10.json
  $PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/warehouse-2000" --budget-ms 100 --agents 2000 --steps 1000 \
    --title "warehouse_large (MR23-I-10), first 2,000 agents" --problems $L/2023/warehouse.domain/MR23-I-10.json
fi
# Full-size LoRR warehouses, 10,000 agents x 5,000 steps (1-6 min and ~6 GB each): FULL_WAREHOUSE=1.
if [ "${FULL_WAREHOUSE:-0}" = 1 ]; then
  $PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/MR23-I-10-full" --budget-ms 100 \
    --title "warehouse_large (MR23-I-10), 10,000 agents" --problems $L/2023/warehouse.domain/MR23-I-10.json
  $PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/WAREHOUSE-full" --budget-ms 100 --solvers pibt rtlacam \
    --title "LoRR 2024 WAREHOUSE, 10,000 agents" --problems $L/2024/warehouse.domain/WAREHOUSE.json
  $PY scripts/lifelong_sweep.py --bin "$BIN" --out-dir "$OUT/WAREHOUSE-full-reassign" --budget-ms 100 --solvers rtlacam --reassign \
    --title "LoRR 2024 WAREHOUSE, 10,000 agents, reassignment" --problems $L/2024/warehouse.domain/WAREHOUSE.json
fi
echo "tables: $OUT/*/table.md"
