#!/bin/bash
# RT-LaCAM* (default options) at CUTOFF (default 1) ms per iteration, 13 cells of bench_refine.py x scens 1-5:
# one line per run (map, N, scen, solved, valid, executed SOC/LB). Only rtlacam*, so it runs
# in a few minutes where the four-solver sweep takes far longer on a loaded machine.
# EXTRA: more rtlacam-bench flags (e.g. EXTRA=--scatter).
cd "$(dirname "$0")/.."
M=../shared/benchmarks/movingai
for cell in "random-32-32-20 100 200 300 400" "room-32-32-4 50 100 150" "warehouse-10-20-10-2-1 100 200 300 400 500 600"; do
  set -- $cell; m=$1; shift
  for n in "$@"; do for k in 1 2 3 4 5; do
    ./build/apps/rtlacam-bench --map $M/$m.map --scen $M/$m-random-$k.scen -N $n --solver rtlacam --cutoff-ms ${CUTOFF:-1} --refine --seed 0 --timeout-s 20 $EXTRA --json --progress-s 0 2>/dev/null | tail -1 | python3 -c "import json,sys; j=json.loads(sys.stdin.read()); print('$m', $n, $k, j['solved'], j['valid'], round(j['soc']/j['soc_lb'],3) if j['solved'] else 'inf')"
  done; done
done
