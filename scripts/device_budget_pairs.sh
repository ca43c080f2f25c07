#!/usr/bin/env bash
# Issue 22's budget cells with two binaries co-running two at a time (new and main per instance,
# so both see the same machine), scens 1-3: random-32-32-20 N=300 and warehouse-10-20-10-2-1
# N=400 at 0.1/1/10 ms, warehouse-20-40-10-2-2 N=1000 at 0.1/1/10 ms. One line per run: SOC/LB
# (standard), p99 and max iteration CPU ms. DEVDIR as for device_issue22.sh (bin/rtlacam-bench.new,
# bin/rtlacam-bench.main, maps/). Running six or eight at once on one machine inflates both
# binaries' spikes (docs/rt_lacam_star.md), hence two.
#   DEVDIR=devbench OUT=/tmp/out scripts/device_budget_pairs.sh
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-/tmp/devout}; mkdir -p "$OUT"
DEVDIR=${DEVDIR:-devbench}
B=$DEVDIR/bin; M=$DEVDIR/maps
[[ -x $B/rtlacam-bench.new && -x $B/rtlacam-bench.main ]] || { echo "device_budget_pairs.sh: $B lacks rtlacam-bench.new or .main" >&2; exit 2; }
for cell in "random-32-32-20 300" "warehouse-10-20-10-2-1 400" "warehouse-20-40-10-2-2 1000"; do
  read -r m n <<<"$cell"; for k in 1 2 3; do for c in 0.1 1 10; do for b in new main; do echo "$b $m $n $k $c"; done; done; done; done |
xargs -P 2 -I{} bash -c 'read -r b m n k c <<<"{}"; j=$('$B'/rtlacam-bench.$b --map '$M'/$m.map --scen '$M'/$m-random-$k.scen -N $n --solver rtlacam --cutoff-ms $c --json --progress-s 0 --timeout-s 120 2>/dev/null); echo "$b $m $n scen $k cutoff $c $(python3 -c "import json,sys; j=json.loads(sys.argv[1]); print(round(j[\"norm_soc\"],4), round(j[\"p99_iteration_cpu_ms\"],3), round(j[\"max_iteration_cpu_ms\"],3))" "$j")"' | tee "$OUT/pairs.txt"
