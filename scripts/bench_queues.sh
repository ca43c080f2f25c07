#!/usr/bin/env bash
# Station queues and admission (tasks.queues, tasks/station_queues.hpp) on and off, lifelong
# in SUMO (issue 20's "no collapse", issue 24's "parking and queues"): the huge warehouse
# (config/huge_warehouse_lifelong.yaml, 1000 AGVs, 5 expansions per SUMO step) and the large
# one (config/large_warehouse_lifelong.yaml, 200 AGVs, made deterministic with 5 expansions
# per SUMO step, and keep_priorities: true as with queues it must be: waiting AGVs gain
# priority). Off = tasks.queues.capacity 0 (everything else the same), run in the same
# session. Prints per run: errands per tick in each WINDOW of ticks, the last 1000 ticks
# over the first 1000 (issue 20's target: >= 0.8 at 1000 AGVs), collisions, jumps, and the
# on / off ratio of errands per tick.
#
# Usage: scripts/bench_queues.sh [BUILD_DIR] [TICKS] [OUT_DIR]
#   BUILD_DIR  where rtlacam-sumo was built (default: build)
#   TICKS      ticks of the huge runs (default 3000; the large runs: LARGE_TICKS, 1000)
#   OUT_DIR    run outputs + queues.md (default: out/bench_queues)
# QUEUES (env): the on setting (default "{capacity: 1, length: 8}"); WINDOW (500);
# SKIP_HUGE=1 / SKIP_LARGE=1 leave one scenario out; TABLE_ONLY=1 tabulates OUT_DIR again.
# Runs go one after the other (each single-threaded); at 1000 AGVs 3000 ticks took ~50 min
# each on the shared 2-core VM under load (~4 min idle, s27's numbers).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
TICKS="${2:-3000}"
OUT="${3:-$ROOT/out/bench_queues}"
LARGE_TICKS="${LARGE_TICKS:-1000}"
QUEUES="${QUEUES:-{capacity: 1, length: 8\}}"
WINDOW="${WINDOW:-500}"
APP="$BUILD/apps/rtlacam-sumo"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
[ -x "$APP" ] || { echo "bench_queues: $APP not built (cmake --build $BUILD --target rtlacam-sumo)" >&2; exit 1; }
mkdir -p "$OUT"

# A copy of CONFIG in OUT (relative paths made absolute) with tasks.queues set.
variant() {  # config name queues-yaml [extra sed]
  local cfg="$1" name="$2" q="$3"
  sed -e "s#\.\./sumo_scenarios#$ROOT/sumo_scenarios#" -e '/^  queues:/d' \
      -e "s#^  assigner: greedy.*#  assigner: greedy\n  queues: $q#" \
      -e "s#^  budget_ms: 1.0#  budget_ms: 0\n  expansions: 5#" \
      -e "s#^  keep_priorities: false.*#  keep_priorities: true#" "$cfg" > "$OUT/$name.yaml"
}
run() {  # name ticks
  [ -z "${TABLE_ONLY:-}" ] || return 0
  echo "== $1: $2 ticks" >&2
  local rc=0
  nice "$APP" "$OUT/$1.yaml" --max-ticks "$2" --out "$OUT/$1" > "$OUT/$1.log" 2>&1 || rc=$?
  [ "$rc" -eq 0 ] || { echo "bench_queues: $1 exited $rc:" >&2; tail -3 "$OUT/$1.log" >&2; }
}
runs=()
if [ -z "${SKIP_HUGE:-}" ]; then
  variant "$ROOT/config/huge_warehouse_lifelong.yaml" huge_off "{capacity: 0}"
  variant "$ROOT/config/huge_warehouse_lifelong.yaml" huge_on "$QUEUES"
  run huge_off "$TICKS"; run huge_on "$TICKS"; runs+=(huge_off huge_on)
fi
if [ -z "${SKIP_LARGE:-}" ]; then
  variant "$ROOT/config/large_warehouse_lifelong.yaml" large_off "{capacity: 0}"
  variant "$ROOT/config/large_warehouse_lifelong.yaml" large_on "$QUEUES"
  run large_off "$LARGE_TICKS"; run large_on "$LARGE_TICKS"; runs+=(large_off large_on)
fi
python3 - "$OUT" "$WINDOW" "${runs[@]}" <<'PY' | tee "$OUT/queues.md"
import json, os, sys
out, window, runs = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
rate = {}
print(f"| run | ticks | errands/tick per {window} ticks | errands/tick | last 1000 / first 1000 | collisions | jumps | max heading | queued AGV-ticks | error |")
print("|---|---|---|---|---|---|---|---|---|---|")
for r in runs:
    try:
        m = json.load(open(os.path.join(out, r, "metrics.json")))
        ev = json.load(open(os.path.join(out, r, "lifelong.json")))["events"]
    except (OSError, ValueError, KeyError) as e:
        print(f"| {r} | - | - | - | - | - | - | - | - | {e} |")
        continue
    ticks = m["ticks"]
    per = [0] * ((ticks + window - 1) // window)
    for t, *_ in ev:
        per[min((t - 1) // window, len(per) - 1)] += 1
    wins = " ".join(f"{n / min(window, ticks - k * window):.2f}" for k, n in enumerate(per))
    first = sum(1 for t, *_ in ev if t <= 1000) / min(1000, ticks)
    last = sum(1 for t, *_ in ev if t > ticks - 1000) / min(1000, ticks)
    ratio = f"{last / first:.2f}" if first > 0 else "-"
    ll = m["lifelong"]
    rate[r] = ll["errandThroughput"]
    jumps = m["teleports_or_jumps"]
    print(f"| {r} | {ticks} | {wins} | {ll['errandThroughput']:.3f} | {ratio} | {m['collisions']} | {jumps} | "
          f"{ll['queues']['maxHeading']} | {ll['queues']['queuedTicks']} | {m['error']} |")
for s in ("huge", "large"):
    if rate.get(s + "_off"):
        print(f"\n{s}: errands/tick on / off = {rate.get(s + '_on', 0) / rate[s + '_off']:.2f}")
PY
