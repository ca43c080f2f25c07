#!/usr/bin/env bash
# Reproduce Fig. 2 of the RT-LaCAM paper (Liang, Veerapaneni et al., SoCS 2025):
# maps x agent counts x scens x {rtlacam, naive} x cutoffs {0.01, 0.1, 1, 10, 100} ms,
# plus pibt and full-horizon lacam once per instance. One JSON line per run is appended to
# <out>/results.jsonl; runs already there are skipped (an interrupted sweep resumes).
# Then scripts/plot_fig2.py draws <out>/fig2.png and <out>/fig2.md.
# rtlacam and naive run the paper's planner: rtlacam-bench --no-refine --no-reserve --no-resumable (RT-LaCAM
# without LaCAM* refinement, expanding until the cutoff as the paper's loop). --star runs
# RT-LaCAM* instead (rtlacam-bench's defaults) into out/fig2-star, for the second figure.
#
#   scripts/paper_fig2.sh                 # small default: 3 maps x 3 N x 2 scens, 5 s, ~5 min on 2 cores
#   scripts/paper_fig2.sh --full          # the paper's setup: 4 maps, 25 scens, 60 s (days of CPU)
#   scripts/paper_fig2.sh --help
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

usage() {
  cat <<'EOF'
Usage: scripts/paper_fig2.sh [options]

  --full                 the paper's setup: 4 maps, more agent counts, 25 scens, 60 s timeout
  --star                 RT-LaCAM* (rtlacam-bench's defaults: LaCAM* refinement, LNS, SUO, the budget
                         kept) for rtlacam/naive instead of the paper's RT-LaCAM (default:
                         --no-refine --no-reserve); default out dir out/fig2-star
  --out-dir DIR          output directory (default: out/fig2); results in DIR/results.jsonl
  --bench PATH           rtlacam-bench binary (default: build/apps/rtlacam-bench)
  --maps "M1 M2 ..."     map names (files data/movingai/<M>.map and <M>-random-<k>.scen)
  --agents "N1 N2 ..."   agent counts for every map (default: a per-map list, see below)
  --scens K              use scens 1..K (default 2; --full 25)
  --cutoffs "C1 ..."     per-iteration cutoffs in ms (default "0.01 0.1 1 10 100")
  --solvers "S1 ..."     solvers (default "lacam pibt rtlacam naive"; cutoffs apply to rtlacam/naive)
  --timeout-s T          limit on cumulative planning time per run (default 5; --full 60)
  --max-steps S          step limit for rtlacam/naive (default 1000000: large enough that only the
                         planning timeout ends a run, so rtlacam can match lacam's success rate)
  --pibt-max-steps S     step limit for pibt (default 10000; PIBT has no timeout-bounded search)
  --seed K               random seed (default 0)
  --no-swap              PIBT without swap (paper-faithful vanilla LaCAM; default: swap on)
  -j, --jobs P           parallel runs (default 2)
  --no-plot              do not call the plot script
  --dry-run              print the run list and exit
  --csv FILE             write the runs as a sweep CSV for scripts/sweep.py (GNU parallel on
                         several hosts, or a Slurm job array; docs/sweeps.md) and exit
  -h, --help             this help

Environment: PYTHON (default /usr/bin/python3, needs matplotlib) runs scripts/plot_fig2.py.

Default agent counts:      small                 --full
  random-32-32-20          50 150 300            50 100 150 200 250 300 350 400
  room-32-32-4             25 75 150             25 50 75 100 125 150
  warehouse-10-20-10-2-1   100 300 600           100 200 300 400 500 600 700 800 900 1000
  empty-32-32              (not in small)        100 200 300 400 500
A failed run (timeout, step limit or crash) is counted as the timeout in the time plot.
EOF
}

FULL=0
STAR=0
OUT_DIR=""
BENCH="$ROOT/build/apps/rtlacam-bench"
MAPS=""
AGENTS=""
SCENS=""
CUTOFFS="0.01 0.1 1 10 100"
SOLVERS="lacam pibt rtlacam naive"
TIMEOUT=""
MAX_STEPS=1000000
PIBT_MAX_STEPS=10000
SEED=0
SWAP=1
JOBS=2
PLOT=1
DRY=0
CSV=""

need() { [[ $# -ge 2 && -n "$2" ]] || { echo "paper_fig2.sh: $1 needs a value" >&2; exit 2; }; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --full) FULL=1; shift ;;
    --star) STAR=1; shift ;;
    --out-dir) need "$@"; OUT_DIR="$2"; shift 2 ;;
    --bench) need "$@"; BENCH="$2"; shift 2 ;;
    --maps) need "$@"; MAPS="$2"; shift 2 ;;
    --agents) need "$@"; AGENTS="$2"; shift 2 ;;
    --scens) need "$@"; SCENS="$2"; shift 2 ;;
    --cutoffs) need "$@"; CUTOFFS="$2"; shift 2 ;;
    --solvers) need "$@"; SOLVERS="$2"; shift 2 ;;
    --timeout-s) need "$@"; TIMEOUT="$2"; shift 2 ;;
    --max-steps) need "$@"; MAX_STEPS="$2"; shift 2 ;;
    --pibt-max-steps) need "$@"; PIBT_MAX_STEPS="$2"; shift 2 ;;
    --seed) need "$@"; SEED="$2"; shift 2 ;;
    --no-swap) SWAP=0; shift ;;
    -j|--jobs) need "$@"; JOBS="$2"; shift 2 ;;
    --no-plot) PLOT=0; shift ;;
    --dry-run) DRY=1; shift ;;
    --csv) need "$@"; CSV="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "paper_fig2.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

if [[ $FULL == 1 ]]; then
  : "${MAPS:=random-32-32-20 room-32-32-4 warehouse-10-20-10-2-1 empty-32-32}"
  : "${SCENS:=25}"
  : "${TIMEOUT:=60}"
else
  : "${MAPS:=random-32-32-20 room-32-32-4 warehouse-10-20-10-2-1}"
  : "${SCENS:=2}"
  : "${TIMEOUT:=5}"
fi

agents_for() {  # default agent counts per map
  if [[ -n "$AGENTS" ]]; then echo "$AGENTS"; return; fi
  if [[ $FULL == 1 ]]; then
    case "$1" in
      random-32-32-20) echo "50 100 150 200 250 300 350 400" ;;
      room-32-32-4) echo "25 50 75 100 125 150" ;;
      warehouse-10-20-10-2-1) echo "100 200 300 400 500 600 700 800 900 1000" ;;
      empty-32-32) echo "100 200 300 400 500" ;;
      *) echo "50 100 200" ;;
    esac
  else
    case "$1" in
      random-32-32-20) echo "50 150 300" ;;
      room-32-32-4) echo "25 75 150" ;;
      warehouse-10-20-10-2-1) echo "100 300 600" ;;
      empty-32-32) echo "100 250 400" ;;
      *) echo "50 100 200" ;;
    esac
  fi
}

# The planner behind rtlacam / naive (part of each run's key, so the two never mix).
if [[ $STAR == 1 ]]; then PLANNER=star; PLANNER_ARGS=""; : "${OUT_DIR:=$ROOT/out/fig2-star}"
else PLANNER=paper; PLANNER_ARGS="--no-refine --no-reserve --no-resumable"; : "${OUT_DIR:=$ROOT/out/fig2}"; fi

DATA="$ROOT/data/movingai"
[[ -x "$BENCH" ]] || { echo "paper_fig2.sh: bench binary '$BENCH' not found or not executable (build it, or pass --bench)" >&2; exit 2; }
for m in $MAPS; do
  [[ -f "$DATA/$m.map" ]] || { echo "paper_fig2.sh: missing map $DATA/$m.map" >&2; exit 2; }
  for ((k = 1; k <= SCENS; k++)); do
    [[ -f "$DATA/$m-random-$k.scen" ]] || { echo "paper_fig2.sh: missing scen $DATA/$m-random-$k.scen" >&2; exit 2; }
  done
done

mkdir -p "$OUT_DIR"
OUT_DIR="$(cd "$OUT_DIR" && pwd)"
RESULTS="$OUT_DIR/results.jsonl"
ERRORS="$OUT_DIR/errors.log"
touch "$RESULTS"
[[ -n "$CSV" ]] || : >"$ERRORS"   # crashes of earlier invocations are retried below (they are not in results)

# ---- run list: one line "key map k N solver cutoff" per run -----------------------------
# key identifies a run for resuming: map|scen|N|solver|cutoff|seed|swap|timeout[|paper or star]
ALL="$OUT_DIR/.runs.all"
TODO="$OUT_DIR/.runs.todo"
: >"$ALL"
for m in $MAPS; do
  for n in $(agents_for "$m"); do
    for ((k = 1; k <= SCENS; k++)); do
      for s in $SOLVERS; do
        case "$s" in
          rtlacam|naive) cs="$CUTOFFS" ;;
          lacam|pibt) cs="-" ;;
          *) echo "paper_fig2.sh: unknown solver '$s'" >&2; exit 2 ;;
        esac
        tag=""
        [[ "$cs" != "-" ]] && tag="|$PLANNER"
        for c in $cs; do
          echo "$m|$k|$n|$s|$c|s$SEED|swap$SWAP|t$TIMEOUT$tag $m $k $n $s $c" >>"$ALL"
        done
      done
    done
  done
done
if [[ -n "$CSV" ]]; then  # the same runs for scripts/sweep.py (paths relative to the checkout)
  {
    echo "key,map,scen,agents,solver,cutoff_ms,timeout_s,seed,no_swap,max_steps,no_refine,no_reserve"
    while read -r key m k n s c; do
      steps=$MAX_STEPS
      [[ "$s" == pibt ]] && steps=$PIBT_MAX_STEPS
      paper=false
      [[ "$c" != "-" && $PLANNER == paper ]] && paper=true
      [[ "$c" == "-" ]] && c=""
      echo "${key//|/_},data/movingai/$m.map,data/movingai/$m-random-$k.scen,$n,$s,$c,$TIMEOUT,$SEED,$([[ $SWAP == 0 ]] && echo true || echo false),$steps,$paper,$paper"
    done <"$ALL"
  } >"$CSV"
  rm -f "$ALL"
  echo "fig2 sweep: $(($(wc -l <"$CSV") - 1)) runs written to $CSV (scripts/sweep.py parallel|slurm $CSV OUT; then collect)"
  exit 0
fi
source "$(dirname "${BASH_SOURCE[0]}")/lib/sweep.sh"
pending_runs "$ALL" "$RESULTS" "$TODO"

if [[ $PLANNER == paper ]]; then
  echo "fig2 sweep: rtlacam/naive = the paper's RT-LaCAM (rtlacam-bench $PLANNER_ARGS)"
else
  echo "fig2 sweep: rtlacam/naive = RT-LaCAM* (rtlacam-bench's defaults; --star)"
fi
echo "fig2 sweep: maps [$MAPS], scens 1..$SCENS, cutoffs [$CUTOFFS] ms, timeout ${TIMEOUT}s, swap=$SWAP, seed=$SEED"
echo "fig2 sweep: $TOTAL runs, $SKIPPED already in $RESULTS, $PENDING to do with $JOBS parallel jobs"
if [[ $DRY == 1 ]]; then cut -d' ' -f2- "$TODO"; exit 0; fi

# ---- one run ----------------------------------------------------------------------------
COUNTER="$OUT_DIR/.counter"
export BENCH DATA RESULTS ERRORS COUNTER TOTAL TIMEOUT MAX_STEPS PIBT_MAX_STEPS SEED SWAP PLANNER_ARGS

run_one() {
  local key=$1 m=$2 k=$3 n=$4 s=$5 c=$6
  local args=(--map "$DATA/$m.map" --scen "$DATA/$m-random-$k.scen" -N "$n" --solver "$s"
              --timeout-s "$TIMEOUT" --seed "$SEED" --json)
  # shellcheck disable=SC2206  # PLANNER_ARGS: words
  [[ "$c" != "-" ]] && args+=(--cutoff-ms "$c" $PLANNER_ARGS)
  [[ "$SWAP" == 0 ]] && args+=(--no-swap)
  local steps=$MAX_STEPS
  [[ "$s" == pibt ]] && steps=$PIBT_MAX_STEPS
  args+=(--max-steps "$steps")
  bench_record "\"run_key\":\"$key\",\"scen_k\":$k,\"timeout_s\":$TIMEOUT,\"max_steps\":$steps" "${args[@]}"
  local done
  done=$(count_done)
  printf '[%d/%d] %-24s N=%-4s scen=%-2s %-7s cutoff=%-5s %s\n' "$done" "$TOTAL" "$m" "$n" "$k" "$s" "$c" "$MSG"
}
run_pending fig2 "$ALL" "$TODO" "$JOBS"

if [[ $PLOT == 1 ]]; then
  "${PYTHON:-/usr/bin/python3}" "$ROOT/scripts/plot_fig2.py" "$RESULTS" \
    --png "$OUT_DIR/fig2.png" --md "$OUT_DIR/fig2.md"
fi
