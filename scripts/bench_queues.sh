#!/usr/bin/env bash
# Station queues and admission (tasks.queues, tasks/station_queues.hpp) on and off, lifelong
# in SUMO (issue 20's "no collapse", issue 24's "parking and queues"): the huge warehouse
# (config/huge_warehouse_lifelong.yaml, 1000 AGVs, 5 expansions per SUMO step) and the large
# one (config/large_warehouse_lifelong.yaml, 200 AGVs, made deterministic with 5 expansions
# per SUMO step). Off = tasks.queues.capacity 0 with planner.keep_priorities: false (the
# setting the s27 jam was measured with; with true and no queues these dead-end stations
# deadlock early: huge 0.09, large 0.008 errands/tick); on = queues with keep_priorities:
# true (waiting AGVs must gain priority: with false, large 0.048). Run in the same session. Prints per run: errands per tick in each WINDOW of ticks, the last 1000 ticks
# over the first 1000 (issue 20's target: >= 0.8 at 1000 AGVs), collisions, jumps, and the
# on / off ratio of errands per tick.
#
# Usage: scripts/bench_queues.sh [BUILD_DIR] [TICKS] [OUT_DIR]
#   BUILD_DIR  where rtlacam-sumo was built (default: build)
#   TICKS      ticks of the huge runs (default 3000; the large runs: LARGE_TICKS, 1000)
#   OUT_DIR    run outputs + queues.md (default: out/bench_queues)
# QUEUES (env): the on setting (default "{capacity: 1, length: 8}"); WINDOW (500);
# SKIP_HUGE=1 / SKIP_LARGE=1 / SKIP_TWIN=1 leave a part out; TABLE_ONLY=1 tabulates OUT_DIR again.
# The grid twin (first, seconds to minutes): rtlacam-lifelong on the gridified huge net
# (rtlacam-gridify --map), 1000 agents on random cells, 100,000 random pick-up -> drop tasks
# between its stations, pool, 40 expansions per step (5 per SUMO step x 8), off
# (--reset-priorities) and on.
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
variant() {  # config name queues-yaml keep-priorities
  local cfg="$1" name="$2" q="$3" keep="$4"
  sed -e "s#\.\./sumo_scenarios#$ROOT/sumo_scenarios#" -e '/^  queues:/d' \
      -e "s#^  assigner: greedy.*#  assigner: greedy\n  queues: $q#" \
      -e "s#^  budget_ms: 1.0#  budget_ms: 0\n  expansions: 5#" \
      -e "s#^  keep_priorities: .*#  keep_priorities: $keep#" "$cfg" > "$OUT/$name.yaml"
}
run() {  # name ticks
  [ -z "${TABLE_ONLY:-}" ] || return 0
  echo "== $1: $2 ticks" >&2
  local rc=0
  nice "$APP" "$OUT/$1.yaml" --max-ticks "$2" --out "$OUT/$1" > "$OUT/$1.log" 2>&1 || rc=$?
  [ "$rc" -eq 0 ] || { echo "bench_queues: $1 exited $rc:" >&2; tail -3 "$OUT/$1.log" >&2; }
}
if [ -z "${SKIP_TWIN:-}" ]; then
  TW="$OUT/twin"
  mkdir -p "$TW/maps" "$TW/agents" "$TW/tasks"
  if [ -z "${TABLE_ONLY:-}" ]; then
    "$BUILD/apps/rtlacam-gridify" "$ROOT/sumo_scenarios/huge.net.xml" --additional "$ROOT/sumo_scenarios/huge.add.xml" \
      --map "$TW/maps/huge.map" --json "$TW/huge.json" -q
    python3 - "$TW" <<'PY'
import json, random, sys
tw = sys.argv[1]
j = json.load(open(f"{tw}/huge.json"))
w = j["grid"]["width"]
cell = [c["row"] * w + c["col"] for c in j["cells"]]
pick = [cell[s["cell"]] for s in j["stations"] if s["kind"] == "pickup"]
drop = [cell[s["cell"]] for s in j["stations"] if s["kind"] == "drop"]
rnd = random.Random(1)
open(f"{tw}/agents/huge.agents", "w").write("1000\n" + "\n".join(map(str, rnd.sample(cell, 1000))) + "\n")
open(f"{tw}/tasks/huge.tasks", "w").write("# 2024\n100000\n" + "\n".join(
    f"{rnd.choice(pick)},{rnd.choice(drop)}" for _ in range(100000)) + "\n")
json.dump({"mapFile": "maps/huge.map", "agentFile": "agents/huge.agents", "teamSize": 1000,
           "taskFile": "tasks/huge.tasks", "numTasksReveal": 1.5, "version": "2024 LoRR"}, open(f"{tw}/huge.json", "w"))
PY
    for q in 0 1; do
      echo "== twin, queue capacity $q: $TICKS steps" >&2
      reset=""; [ "$q" = 1 ] || reset="--reset-priorities"  # as keep_priorities above
      nice "$BUILD/apps/rtlacam-lifelong" --problem "$TW/huge.json" --steps "$TICKS" --budget-ms 1000 --budget-expansions 40 \
        --solver rtlacam --quiet $reset --queue-capacity "$q" --queue-length 8 --out "$TW/q$q.log.json" > "$TW/q$q.json"
    done
  fi
  python3 - "$TW" "$WINDOW" <<'PY' | tee "$OUT/twin.md"
import json, sys
tw, window = sys.argv[1], int(sys.argv[2])
print(f"| grid twin | steps | errands/step per {window} steps | errands/step | last 1000 / first 1000 | planner errors |")
print("|---|---|---|---|---|---|")
rate = {}
for q in (0, 1):
    j = json.load(open(f"{tw}/q{q}.json"))
    ev = json.load(open(f"{tw}/q{q}.log.json"))["events"]
    n = j["makespan"]
    per = [0] * ((n + window - 1) // window)
    for t, *_ in ev:
        per[min((t - 1) // window, len(per) - 1)] += 1
    first = sum(1 for t, *_ in ev if t <= 1000) / min(1000, n)
    last = sum(1 for t, *_ in ev if t > n - 1000) / min(1000, n)
    rate[q] = j["errandThroughput"]
    print(f"| queues {'on' if q else 'off'} | {n} | {' '.join(f'{k / window:.2f}' for k in per)} | {j['errandThroughput']:.3f} | "
          f"{last / first if first else 0:.2f} | {j['numPlannerErrors']} |")
if rate[0]:
    print(f"\ngrid twin: errands/step on / off = {rate[1] / rate[0]:.2f}")
PY
fi
runs=()
if [ -z "${SKIP_HUGE:-}" ]; then
  variant "$ROOT/config/huge_warehouse_lifelong.yaml" huge_off "{capacity: 0}" false
  variant "$ROOT/config/huge_warehouse_lifelong.yaml" huge_on "$QUEUES" true
  run huge_off "$TICKS"; run huge_on "$TICKS"; runs+=(huge_off huge_on)
fi
if [ -z "${SKIP_LARGE:-}" ]; then
  variant "$ROOT/config/large_warehouse_lifelong.yaml" large_off "{capacity: 0}" false
  variant "$ROOT/config/large_warehouse_lifelong.yaml" large_on "$QUEUES" true
  run large_off "$LARGE_TICKS"; run large_on "$LARGE_TICKS"; runs+=(large_off large_on)
fi
[ ${#runs[@]} -gt 0 ] || exit 0
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
