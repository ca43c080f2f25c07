#!/usr/bin/env bash
# Issue 22 on a many-core machine, in one go: the iteration budget (scens 1-3, cutoffs 0.1/1/10 ms,
# `BINS` binaries, 8 runs at once) and then quality against lacam3 over the 65 cells of the issue
# (peer_bench.py, JOBS instances at once, variants 1 ms and 0.01 ms). DEVDIR holds bin/
# (rtlacam-bench.new, rtlacam-bench.main, rtlacam-check, lacam3) and maps/ (the .map and
# -random-1..5.scen files); it is copied there because the machine has no ../shared.
#   DEVDIR=devbench BINS="new main" JOBS=4 OUT=/tmp/out scripts/device_issue22.sh   (QUICK=1: a smoke run)
# PEER_CELLS / PEER_SCENS replace the 65 cells; EXTRA_VARIANT="name=options" adds a variant of ours;
# PAR (default 8) budget runs at once.
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-/tmp/devout}; mkdir -p "$OUT"
DEVDIR=${DEVDIR:-devbench}
B=$DEVDIR/bin; M=$DEVDIR/maps
[[ -x $B/rtlacam-bench.new && -x $B/rtlacam-check && -x $B/lacam3 ]] || { echo "device_issue22.sh: $B lacks rtlacam-bench.new, rtlacam-check or lacam3" >&2; exit 2; }
nproc; uname -a | cut -c1-100
export MOVINGAI_DIR="$PWD/$M"  # peer_bench.py looks there first
QUICK=${QUICK:-0}
if [[ $QUICK == 1 ]]; then CELLS="random-32-32-20 100"; CUTS="1"; SCENS="1"; BINS="new"; else
  CELLS="random-32-32-20 300|warehouse-10-20-10-2-1 400|warehouse-20-40-10-2-2 1000"; CUTS="0.1 1 10"; SCENS="1 2 3"; BINS="${BINS:-new main}"; fi
jobs=()
IFS='|' read -ra CL <<<"$CELLS"
for b in $BINS; do for cell in "${CL[@]}"; do read -r m n <<<"$cell"; for c in $CUTS; do for k in $SCENS; do
  jobs+=("$b $m $n $c $k"); done; done; done; done
printf '%s\n' "${jobs[@]}" | xargs -P ${PAR:-8} -I{} bash -c 'read -r b m n c k <<<"{}"; j=$('$B'/rtlacam-bench.$b --map '$M'/$m.map --scen '$M'/$m-random-$k.scen -N $n --solver rtlacam --cutoff-ms $c --json --progress-s 0 --timeout-s 120 2>/dev/null); echo "$b $m $n $c $k $(python3 -c "import json,sys; j=json.loads(sys.argv[1]); print(j[\"solved\"], j[\"valid\"], round(j[\"norm_soc\"],4), round(j.get(\"p99_iteration_cpu_ms\",0),4), round(j.get(\"max_iteration_cpu_ms\",0),4), round(j[\"p99_iteration_ms\"],4), round(j[\"max_iteration_ms\"],4))" "$j")"' > "$OUT/budget.txt"
echo "# bin map N cutoff scen solved valid SOC/LB p99cpu maxcpu p99wall maxwall"; sort "$OUT/budget.txt"
date
if [[ $QUICK == 1 ]]; then PC="random-32-32-20:50"; PS="1"; PT=1; else
  PC="${PEER_CELLS:-random-32-32-20:100,200,300,400 warehouse-10-20-10-2-1:100,200,300,400,500,600 room-32-32-4:50,100,150}"; PS="${PEER_SCENS:-1 2 3 4 5}"; PT=10; fi
PYTHONUNBUFFERED=1 python3 scripts/peer_bench.py --bench $B/rtlacam-bench.new --check $B/rtlacam-check --lacam3 $B/lacam3 \
  --cells $PC --scens $PS --peer-time-s $PT --jobs ${JOBS:-4} --variant c1="--cutoff-ms 1" --variant c001="--cutoff-ms 0.01" \
  ${EXTRA_VARIANT:+--variant "$EXTRA_VARIANT"} 2>&1 | tee "$OUT/peer.txt"
date
