#!/usr/bin/env bash
# Iteration budget of RT-LaCAM* on the cells of issue 22: random-32-32-20 N=300,
# warehouse-10-20-10-2-1 N=400, warehouse-20-40-10-2-2 N=1000 (scen 1) at cutoffs 0.1, 1 and
# 10 ms, one line per run: SOC/LB (standard), loss/LB, p99 / max iteration time on the
# planning thread's CPU (what preemption on a loaded box does not inflate) and on the wall.
# Give a second binary (an older build) to measure before and after in one run, one after
# the other (an older binary prints no CPU times or loss: 0). An argument may carry options
# for its binary after it, in one word, e.g. the two objectives of one build:
#
#   scripts/refine_budget_cells.sh build/apps/rtlacam-bench [/path/to/old/rtlacam-bench]
#   scripts/refine_budget_cells.sh "build/apps/rtlacam-bench --objective loss" build/apps/rtlacam-bench
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DATA="${DATA:-$ROOT/../shared/benchmarks/movingai}"
[[ $# -ge 1 ]] || { echo "usage: $0 'BENCH [OPTIONS]' ['OLD_BENCH [OPTIONS]']" >&2; exit 2; }
for spec in "$@"; do
  read -r b _ <<<"$spec"
  [[ -x "$b" ]] || { echo "refine_budget_cells.sh: '$b' is not executable" >&2; exit 2; }
done
[[ -f "$DATA/warehouse-20-40-10-2-2.map" ]] || { echo "refine_budget_cells.sh: no maps in $DATA (set DATA)" >&2; exit 2; }
for spec in "$@"; do
  read -r bin opts <<<"$spec"
  echo "# $spec"
  for cell in "random-32-32-20 300" "warehouse-10-20-10-2-1 400" "warehouse-20-40-10-2-2 1000"; do
    read -r m n <<<"$cell"
    for c in 0.1 1 10; do
      "$bin" --map "$DATA/$m.map" --scen "$DATA/$m-random-1.scen" -N "$n" --solver rtlacam --cutoff-ms "$c" \
        --json --progress-s 0 --timeout-s 120 $opts 2>/dev/null |
        python3 -c "import json,sys; j=json.load(sys.stdin); print('%-24s N=%-4d cutoff %-4s solved %d valid %d SOC/LB %.3f loss/LB %.3f cpu p99 %.3f max %.3f | wall p99 %.3f max %.3f' % ('$m', $n, '$c', j['solved'], j['valid'], j['norm_soc'], j.get('norm_loss', 0), j.get('p99_iteration_cpu_ms', 0), j.get('max_iteration_cpu_ms', 0), j['p99_iteration_ms'], j['max_iteration_ms']))"
    done
  done
done
