#!/usr/bin/env bash
# SUMO controller benchmark: 1000 AGVs on the huge warehouse (config/huge_warehouse.yaml,
# sumo_scenarios/huge.net.xml, 4680 cells) driven by RT-LaCAM, once per back end:
#   libsumo (embedded), traci (sumo child process), traci pinned to one core (taskset).
# Reports per run: wall ms per simulated second and the real-time factor, SUMO's own step
# time vs the controller's time (planner + commands + checks) per simulated second and
# their ratio, planner ms per SUMO step p50/p99/max, commands sent, re-syncs, violations.
#
# Usage: scripts/bench_sumo.sh [BUILD_DIR] [TICKS] [OUT_DIR]
#   BUILD_DIR  where rtlacam-sumo was built (default: build)
#   TICKS      max simulated seconds per run (default: 1000; a run stops once every AGV is
#              at its goal, ~410 ticks here; tick = 1 s = 8 SUMO steps)
#   OUT_DIR    run outputs + bench.json (default: out/bench_sumo)
# Target: >= 10x faster than real time, i.e. wall <= 100 ms per simulated second.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
TICKS="${2:-1000}"
OUT="${3:-$ROOT/out/bench_sumo}"
APP="$BUILD/apps/rtlacam-sumo"
CONFIG="${CONFIG:-$ROOT/config/huge_warehouse.yaml}"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
[ -x "$APP" ] || { echo "bench_sumo: $APP not built (cmake --build $BUILD)" >&2; exit 1; }
mkdir -p "$OUT"

run() {  # name, then the command prefix (e.g. taskset -c 1)
  local name="$1"; shift
  local backend=libsumo
  case "$name" in traci*) backend=traci ;; esac
  echo "== $name: $CONFIG, $TICKS ticks" >&2
  local rc=0
  "$@" "$APP" "$CONFIG" --backend "$backend" --max-ticks "$TICKS" --out "$OUT/$name" \
    > "$OUT/$name.log" 2>&1 || rc=$?
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 4 ]; then  # 4: tick limit first (expected)
    echo "bench_sumo: $name failed (exit $rc):" >&2; tail -5 "$OUT/$name.log" >&2; exit 1
  fi
}

run libsumo
run traci
if command -v taskset > /dev/null; then run traci_pinned taskset -c 1; fi

python3 - "$OUT" "$(nproc)" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'EOF'
import json, os, sys
out, ncpu, load = sys.argv[1], sys.argv[2], sys.argv[3]
rows = []
for name in ("libsumo", "traci", "traci_pinned"):
    f = os.path.join(out, name, "metrics.json")
    if not os.path.exists(f):
        continue
    m = json.load(open(f))
    ps, pl = m["ms_per_sim_s"], m["planner_ms_per_step"]
    rows.append({
        "run": name, "agents": m["agents"], "cells": m["cells"], "ticks": m["ticks"], "error": m["error"],
        "wall_ms_per_sim_s": ps["wall"], "x_real_time": 1000.0 / ps["wall"] if ps["wall"] > 0 else 0,
        "sumo_ms_per_sim_s": ps["sumo"], "controller_ms_per_sim_s": ps["controller"],
        "planner_ms_per_sim_s": ps["planner"], "control_ms_per_sim_s": ps["control"],
        "controller_to_sumo": m["controller_to_sumo_ratio"],
        "sumo_ms_per_step_p50": m["sumo_ms_per_step"]["p50"],
        "planner_ms_per_step_p50": pl["p50"], "planner_ms_per_step_p99": pl["p99"], "planner_ms_per_step_max": pl["max"],
        "control_ms_per_tick_p50": m["control_ms_per_tick"]["p50"],
        "commands": m["commands"]["total"], "resyncs": m["resyncs"], "violations": m["violations"],
        "at_goal_solved": m["solved"], "total_wall_s": m["wall_s"],
    })
json.dump({"cpus": int(ncpu), "loadavg": load, "runs": rows}, open(os.path.join(out, "bench.json"), "w"), indent=2)
print(f"1000-AGV SUMO bench ({ncpu} CPUs, load {load}); per simulated second (tick 1 s = 8 SUMO steps):")
hdr = ("run", "ticks", "solved", "wall ms", "x real", "sumo ms", "ctrl ms", "ctrl/sumo", "plan p50", "plan p99", "plan max", "cmds", "resync", "viol")
print("| " + " | ".join(hdr) + " |")
print("|" + "---|" * len(hdr))
for r in rows:
    print(f"| {r['run']} | {r['ticks']} | {'yes' if r['at_goal_solved'] else 'no'} | {r['wall_ms_per_sim_s']:.1f} | {r['x_real_time']:.1f} | {r['sumo_ms_per_sim_s']:.1f} | "
          f"{r['controller_ms_per_sim_s']:.1f} | {r['controller_to_sumo']:.2f} | {r['planner_ms_per_step_p50']:.3f} | "
          f"{r['planner_ms_per_step_p99']:.3f} | {r['planner_ms_per_step_max']:.3f} | {r['commands']} | {r['resyncs']} | "
          f"{r['violations']} |")
    if r["error"]:
        print(f"  {r['run']} error: {r['error']}")
ok = all(r["x_real_time"] >= 10 and not r["error"] for r in rows)
print("target >= 10x real time:", "met" if ok else "MISSED", "; details in", os.path.join(out, "bench.json"))
EOF
