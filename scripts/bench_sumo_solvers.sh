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
# SOLVERS (env) the solvers (default: rtlacam pibt pibt-rot epibt wppl); TABLE_ONLY=1 only
# tabulates the runs already in OUT_DIR.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
TICKS="${2:-1000}"
OUT="${3:-$ROOT/out/bench_sumo_solvers}"
APP="$BUILD/apps/rtlacam-sumo"
CONFIG="${CONFIG:-$ROOT/config/large_warehouse_lifelong.yaml}"
SOLVERS="${SOLVERS:-rtlacam pibt pibt-rot epibt wppl}"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
[ -x "$APP" ] || { echo "bench_sumo_solvers: $APP not built (cmake --build $BUILD)" >&2; exit 1; }
mkdir -p "$OUT"
for s in $SOLVERS; do
  [ -z "${TABLE_ONLY:-}" ] || break
  echo "== $s: $CONFIG, $TICKS ticks" >&2
  rc=0
  "$APP" "$CONFIG" --solver "$s" --max-ticks "$TICKS" --out "$OUT/$s" > "$OUT/$s.log" 2>&1 || rc=$?
  [ "$rc" -eq 0 ] || { echo "bench_sumo_solvers: $s exited $rc:" >&2; tail -3 "$OUT/$s.log" >&2; }
done
python3 - "$OUT" $SOLVERS <<'PY' | tee "$OUT/solvers.md"
import json, sys
out, solvers = sys.argv[1], sys.argv[2:]
print("| solver | ticks | errands/tick | collisions | jumps | quarter turns | planner ms/tick p50 | p99 | "
      "planner CPU ms/step p50 | p99 | wall s | error |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for s in solvers:
    try:
        m = json.load(open(f"{out}/{s}/metrics.json"))
    except OSError:
        print(f"| {s} | (no metrics.json) |"); continue
    p, c = m["planner_ms_per_tick"], m["planner_cpu_ms_per_step"]
    print(f"| {s} | {m['ticks']} | {m['lifelong']['errandThroughput']:.3f} | {m['collisions']} | "
          f"{m['teleports_or_jumps']} | {m.get('quarter_turns', 0)} | {p['p50']:.2f} | {p['p99']:.2f} | "
          f"{c['p50']:.3f} | {c['p99']:.3f} | {m['wall_s']:.1f} | {m['error'] or '-'} |")
PY
