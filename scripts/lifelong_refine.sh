#!/bin/bash
# RT-LaCAM* vs RT-LaCAM in lifelong runs (issue 9): the five LoRR 2023 random-32-32-20
# round-robin problems of scripts/lifelong_bench.sh, --refine vs --no-refine at 1 and 10 ms
# per step, seeds 0..SEEDS-1 (default 3; wall-clock budgets make single runs noisy). JSON logs
# in out/lifelong_refine/; one line per run (problem, budget, variant, seed, task throughput,
# planner p99 ms, planner errors), then per problem and budget the mean throughputs and the
# ratio refine / no-refine.
cd "$(dirname "$0")/.."
L=../shared/benchmarks/lorr/2023/random.domain
SEEDS=${SEEDS:-3}
mkdir -p out/lifelong_refine
for b in 1 10; do for p in MR23-I-03 MR23-I-04 MR23-I-05 MR23-I-07 MR23-I-08; do
  for s in $(seq 0 $((SEEDS - 1))); do for r in --refine --no-refine; do
    f=out/lifelong_refine/${p}_${b}ms${r}_s$s.json
    ./build/apps/rtlacam-lifelong --problem $L/$p.json --budget-ms $b $r --seed $s --quiet > $f 2>/dev/null
    echo "$p $b $r $s $(python3 -c "import json; j=json.load(open('$f')); print(j['taskThroughput'], j['plannerTimeStats']['p99'], j['numPlannerErrors'])")"
  done; done
  python3 - "$p" "$b" "$SEEDS" <<'PY'
import json, sys
p, b, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
m = [sum(json.load(open(f'out/lifelong_refine/{p}_{b}ms{r}_s{s}.json'))['taskThroughput'] for s in range(n)) / n
     for r in ('--refine', '--no-refine')]
print(f'MEAN {p} {b}ms refine {m[0]:.3f} no-refine {m[1]:.3f} ratio {m[0] / m[1]:.3f}')
PY
done; done
