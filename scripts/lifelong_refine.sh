#!/bin/bash
# RT-LaCAM* vs RT-LaCAM in lifelong runs (issue 9): the five LoRR 2023 random-32-32-20
# round-robin problems of scripts/lifelong_bench.sh, --refine vs --no-refine at 1 and 10 ms
# per step. JSON logs in out/lifelong_refine/; one line per run: problem, budget, variant,
# throughput, planner p99 ms, planner errors.
cd "$(dirname "$0")/.."
L=../shared/benchmarks/lorr/2023/random.domain
mkdir -p out/lifelong_refine
for b in 1 10; do for p in MR23-I-03 MR23-I-04 MR23-I-05 MR23-I-07 MR23-I-08; do for r in --refine --no-refine; do
  ./build/apps/rtlacam-lifelong --problem $L/$p.json --budget-ms $b $r --quiet > out/lifelong_refine/${p}_${b}ms${r}.json 2>/dev/null
  echo "$p $b $r $(python3 -c "import json; j=json.load(open('out/lifelong_refine/${p}_${b}ms${r}.json')); print(j['throughput'], j['plannerTimes']['p99'], j['numPlannerErrors'])")"
done; done; done
