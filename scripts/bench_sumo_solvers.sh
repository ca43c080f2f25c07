#!/usr/bin/env bash
# Every real-time solver drives the SUMO AGVs of one lifelong scenario (issue 20): the cell
# solvers (rtlacam, pibt) and the rotation solvers (pibt-rot, epibt, wppl: AGVs with a
# heading, quarter turns of fleet.turn_s = 1 s standing on the cell). One run per solver,
# one after the other (single-threaded each), then a table: errands per tick, collisions,
# jumps (moveTo jumps + re-syncs), quarter turns, planner ms per tick p50 / p99 (wall: the
# machine's load shows in them), planner CPU ms per SUMO step p50 / p99, wall s.
#
# Usage: scripts/bench_sumo_solvers.sh [BUILD_DIR] [TICKS] [OUT_DIR]
#   BUILD_DIR  where rtlacam-sumo was built (default: build)
#   TICKS      ticks per run (default: 1000; 1 tick = 1 s = 8 SUMO steps)
#   OUT_DIR    run outputs + solvers.md (default: out/bench_sumo_solvers)
# CONFIG (env) picks the scenario (default: config/large_warehouse_lifelong.yaml, 200 AGVs);
# SOLVERS (env) the solvers (default: rtlacam pibt pibt-rot epibt wppl); EXECUTORS (env) the
# executors each solver runs under (default: lockstep; adg / adg-follow drive the AGVs with
# the vType's kinematics, the rotation solvers' turns on the cell); TABLE_ONLY=1 only
# tabulates the runs already in OUT_DIR. Per run also the free-flow bound (metrics.json
# lifelong.throughputBound: every AGV alone on its executed path, with turns) and the share
# of it reached (throughputOverBound), and the ratio of each run's errands per tick to the
# first executor's run of the same solver (the baseline, measured in the same script run).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
TICKS="${2:-1000}"
OUT="${3:-$ROOT/out/bench_sumo_solvers}"
APP="$BUILD/apps/rtlacam-sumo"
CONFIG="${CONFIG:-$ROOT/config/large_warehouse_lifelong.yaml}"
SOLVERS="${SOLVERS:-rtlacam pibt pibt-rot epibt wppl}"
EXECUTORS="${EXECUTORS:-lockstep}"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
[ -x "$APP" ] || { echo "bench_sumo_solvers: $APP not built (cmake --build $BUILD)" >&2; exit 1; }
mkdir -p "$OUT"
# One output dir per run: <solver> under lockstep alone (as before), <solver>-<executor> else.
run_dir() { if [ "$EXECUTORS" = lockstep ]; then echo "$1"; else echo "$1-$2"; fi; }
for s in $SOLVERS; do
  for e in $EXECUTORS; do
    [ -z "${TABLE_ONLY:-}" ] || break 2
    d="$(run_dir "$s" "$e")"
    echo "== $s under $e: $CONFIG, $TICKS ticks" >&2
    rc=0
    "$APP" "$CONFIG" --solver "$s" --executor "$e" --max-ticks "$TICKS" --out "$OUT/$d" > "$OUT/$d.log" 2>&1 || rc=$?
    [ "$rc" -eq 0 ] || { echo "bench_sumo_solvers: $s ($e) exited $rc:" >&2; tail -3 "$OUT/$d.log" >&2; }
  done
done
python3 - "$OUT" "$EXECUTORS" $SOLVERS <<'PY' | tee "$OUT/solvers.md"
import json, sys
out, executors, solvers = sys.argv[1], sys.argv[2].split(), sys.argv[3:]
def run_dir(s, e): return s if executors == ["lockstep"] else f"{s}-{e}"
print("| solver | executor | ticks | errands/tick | vs " + executors[0] + " | free-flow bound tasks/tick | "
      "share of bound | collisions | jumps | instant flips | quarter turns | planner ms/tick p50 | p99 | "
      "planner CPU ms/step p50 | p99 | wall s | error |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for s in solvers:
    base = None
    for e in executors:
        try:
            m = json.load(open(f"{out}/{run_dir(s, e)}/metrics.json"))
        except OSError:
            print(f"| {s} | {e} | (no metrics.json) |"); continue
        p, c, life = m["planner_ms_per_tick"], m["planner_cpu_ms_per_step"], m["lifelong"]
        ept = life["errandThroughput"]
        if e == executors[0]: base = ept
        ratio = f"{ept / base:.3f}" if base else "-"
        print(f"| {s} | {e} | {m['ticks']} | {ept:.3f} | {ratio} | {life['throughputBound']:.3f} | "
              f"{life['throughputOverBound']:.3f} | {m['collisions']} | {m['teleports_or_jumps']} | "
              f"{m.get('instant_flips', 0)} | {m.get('quarter_turns', 0)} | {p['p50']:.2f} | {p['p99']:.2f} | "
              f"{c['p50']:.3f} | {c['p99']:.3f} | {m['wall_s']:.1f} | {m['error'] or '-'} |")
PY
