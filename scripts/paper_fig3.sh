#!/usr/bin/env bash
# Reproduce Fig. 3 of the RT-LaCAM paper (Liang, Veerapaneni et al., SoCS 2025): a learned
# one-step policy on random-32-32-20, run through CS-PIBT alone (policy + PIBT collision
# shield, no search) vs inside RT-LaCAM, next to RT-LaCAM with the plain distance heuristic.
# Success rate vs number of agents, on the evaluation scens 21..25 (the committed model was
# trained on scens 1..20; policy/README.md). One JSON line per run is appended to
# <out>/results.jsonl; runs already there are skipped (an interrupted sweep resumes). Then
# scripts/plot_fig3.py draws <out>/fig3.png and <out>/fig3.md. The rtlacam series run the
# paper's planner (rtlacam-bench --no-refine --no-reserve --no-resumable), not the CLI's default RT-LaCAM*.
#
#   scripts/paper_fig3.sh                          # default sweep, ~10 min on 2 cores
#   scripts/paper_fig3.sh --out-dir docs/fig3run   # elsewhere
#   scripts/paper_fig3.sh --help
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

usage() {
  cat <<'EOF2'
Usage: scripts/paper_fig3.sh [options]

  --out-dir DIR        output directory (default: out/fig3); results in DIR/results.jsonl
  --bench PATH         rtlacam-bench binary (default: build/apps/rtlacam-bench)
  --policy FILE        weights (default: policy/models/random-32-32-20.bin)
  --map NAME           map (default random-32-32-20; data/movingai/<NAME>.map and -random-<k>.scen)
  --agents "N1 ..."    agent counts (default "50 100 150 200 250 300")
  --scens "K1 ..."     scen indices (default "21 22 23 24 25": not seen in training)
  --solvers "S1 ..."   series (default "cspibt rtlacam-policy rtlacam"; also: pibt, lacam-policy, lacam)
  --cutoff-ms C        RT-LaCAM planning budget per iteration (default 1)
  --timeout-s T        limit on cumulative planning time per run (default 10)
  --max-steps S        step limit of RT-LaCAM runs (default 1000000: only the timeout ends them)
  --pibt-max-steps S   step limit of the searchless runs, cspibt and pibt (default 2000)
  --seed K             random seed (default 0)
  -j, --jobs P         parallel runs (default 2)
  --no-plot            do not call the plot script
  --dry-run            print the run list and exit
  -h, --help           this help

Series: cspibt = PIBT ordered by the policy, no search (CS-PIBT); rtlacam-policy = RT-LaCAM
whose PIBT is ordered by the policy; rtlacam = RT-LaCAM with the distance heuristic; pibt =
PIBT with the distance heuristic; lacam(-policy) = full-horizon LaCAM.
Environment: PYTHON (default /usr/bin/python3, needs matplotlib) runs scripts/plot_fig3.py.
EOF2
}

OUT_DIR="$ROOT/out/fig3"
BENCH="$ROOT/build/apps/rtlacam-bench"
POLICY="$ROOT/policy/models/random-32-32-20.bin"
MAP="random-32-32-20"
AGENTS="50 100 150 200 250 300"
SCENS="21 22 23 24 25"
SOLVERS="cspibt rtlacam-policy rtlacam"
CUTOFF=1
TIMEOUT=10
MAX_STEPS=1000000
PIBT_MAX_STEPS=2000
SEED=0
JOBS=2
PLOT=1
DRY=0

need() { [[ $# -ge 2 && -n "$2" ]] || { echo "paper_fig3.sh: $1 needs a value" >&2; exit 2; }; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out-dir) need "$@"; OUT_DIR="$2"; shift 2 ;;
    --bench) need "$@"; BENCH="$2"; shift 2 ;;
    --policy) need "$@"; POLICY="$2"; shift 2 ;;
    --map) need "$@"; MAP="$2"; shift 2 ;;
    --agents) need "$@"; AGENTS="$2"; shift 2 ;;
    --scens) need "$@"; SCENS="$2"; shift 2 ;;
    --solvers) need "$@"; SOLVERS="$2"; shift 2 ;;
    --cutoff-ms) need "$@"; CUTOFF="$2"; shift 2 ;;
    --timeout-s) need "$@"; TIMEOUT="$2"; shift 2 ;;
    --max-steps) need "$@"; MAX_STEPS="$2"; shift 2 ;;
    --pibt-max-steps) need "$@"; PIBT_MAX_STEPS="$2"; shift 2 ;;
    --seed) need "$@"; SEED="$2"; shift 2 ;;
    -j|--jobs) need "$@"; JOBS="$2"; shift 2 ;;
    --no-plot) PLOT=0; shift ;;
    --dry-run) DRY=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "paper_fig3.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

DATA="$ROOT/data/movingai"
[[ -x "$BENCH" ]] || { echo "paper_fig3.sh: bench binary '$BENCH' not found or not executable (build it, or pass --bench)" >&2; exit 2; }
[[ -f "$POLICY" ]] || { echo "paper_fig3.sh: policy weights '$POLICY' not found" >&2; exit 2; }
POLICY="$(cd "$(dirname "$POLICY")" && pwd)/$(basename "$POLICY")"
[[ -f "$DATA/$MAP.map" ]] || { echo "paper_fig3.sh: missing map $DATA/$MAP.map" >&2; exit 2; }
for k in $SCENS; do
  [[ -f "$DATA/$MAP-random-$k.scen" ]] || { echo "paper_fig3.sh: missing scen $DATA/$MAP-random-$k.scen" >&2; exit 2; }
done
for s in $SOLVERS; do
  case "$s" in cspibt|rtlacam-policy|rtlacam|pibt|lacam-policy|lacam) ;;
    *) echo "paper_fig3.sh: unknown series '$s' (see --help)" >&2; exit 2 ;;
  esac
done

mkdir -p "$OUT_DIR"
OUT_DIR="$(cd "$OUT_DIR" && pwd)"
RESULTS="$OUT_DIR/results.jsonl"
ERRORS="$OUT_DIR/errors.log"
touch "$RESULTS"
: >"$ERRORS"

# ---- run list: "key scen N series" per run; key = map|scen|N|series|cutoff|seed|timeout|policy
ALL="$OUT_DIR/.runs.all"
TODO="$OUT_DIR/.runs.todo"
: >"$ALL"
PKEY=$(basename "$POLICY")
for n in $AGENTS; do
  for k in $SCENS; do
    for s in $SOLVERS; do
      tag=""
      [[ "$s" == rtlacam* ]] && tag="|paper"  # the planner changed: earlier runs were RT-LaCAM*
      echo "$MAP|$k|$n|$s|c$CUTOFF|s$SEED|t$TIMEOUT|$PKEY$tag $k $n $s" >>"$ALL"
    done
  done
done
source "$(dirname "${BASH_SOURCE[0]}")/lib/sweep.sh"
pending_runs "$ALL" "$RESULTS" "$TODO"

echo "fig3 sweep: rtlacam series = the paper's RT-LaCAM (rtlacam-bench --no-refine --no-reserve --no-resumable)"
echo "fig3 sweep: $MAP, N [$AGENTS], scens [$SCENS], series [$SOLVERS], cutoff ${CUTOFF} ms, timeout ${TIMEOUT}s, seed $SEED"
echo "fig3 sweep: $TOTAL runs, $SKIPPED already in $RESULTS, $PENDING to do with $JOBS parallel jobs"
if [[ $DRY == 1 ]]; then cut -d' ' -f2- "$TODO"; exit 0; fi

COUNTER="$OUT_DIR/.counter"
export BENCH DATA MAP POLICY RESULTS ERRORS COUNTER TOTAL CUTOFF TIMEOUT MAX_STEPS PIBT_MAX_STEPS SEED

run_one() {
  local key=$1 k=$2 n=$3 series=$4
  local solver=${series%-policy} steps=$MAX_STEPS
  local args=(--map "$DATA/$MAP.map" --scen "$DATA/$MAP-random-$k.scen" -N "$n" --solver "$solver"
              --timeout-s "$TIMEOUT" --cutoff-ms "$CUTOFF" --seed "$SEED" --json)
  [[ "$series" == *-policy || "$series" == cspibt ]] && args+=(--policy "$POLICY")
  [[ "$solver" == cspibt || "$solver" == pibt ]] && steps=$PIBT_MAX_STEPS
  [[ "$solver" == rtlacam ]] && args+=(--no-refine --no-reserve --no-resumable)  # the paper's RT-LaCAM
  args+=(--max-steps "$steps")
  bench_record "\"run_key\":\"$key\",\"series\":\"$series\",\"scen_k\":$k,\"timeout_s\":$TIMEOUT,\"max_steps\":$steps" "${args[@]}"
  local done
  done=$(count_done)
  printf '[%d/%d] N=%-4s scen=%-2s %-15s %s\n' "$done" "$TOTAL" "$n" "$k" "$series" "$MSG"
}
run_pending fig3 "$ALL" "$TODO" "$JOBS"

if [[ $PLOT == 1 ]]; then
  "${PYTHON:-/usr/bin/python3}" "$ROOT/scripts/plot_fig3.py" "$RESULTS" \
    --png "$OUT_DIR/fig3.png" --md "$OUT_DIR/fig3.md"
fi
