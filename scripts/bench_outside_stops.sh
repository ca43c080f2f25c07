#!/usr/bin/env bash
# Fault bench (issue 21): AGV stops the controller is not told about, injected by a SECOND
# TraCI client (scripts/traci_second_client.py) into an external SUMO of two clients
# (sumo --num-clients 2; rtlacam-sumo joins it with --port P --order 1).
#
# On each net, for each physical executor: one run without outside stops (the baseline of
# the same net, executor and instance), then SEEDS runs in which 10 % of the AGVs are each
# stopped for 1-5 s after every pause of 3-15 s (braked at their vType's decel, held at 0).
# Nets: the shipped small warehouse (16 AGVs), a warehouse of dead-end aisles only
# (sumo_scenarios/tree.net.xml, 10 AGVs), the small net with 2 m cells and 1.6 m AGVs
# (10 AGVs), and a 3 x 3 grid of 8.99 m / 4 m aisles in 1 m cells (tests/data/controller/tolgrid,
# 12 AGVs: aisles within grid.tolerance of whole cells, as netconvert writes random or diagonal
# nets) -- the nets of tests/controller/test_closed_loop.cpp. NETS="..." picks some. No delay model (the only
# stops are the outside ones); planner budget 1 ms; replan_on_stuck as configured (on).
# Per run: exit code, error, solved, makespan, the physical bound and makespan / bound,
# makespan / the baseline's, steps the second client held an AGV, SUMO collisions (second
# client, every step, + collision.xml), max accel / decel from SUMO's fcd against the
# vType's, and AGVs still moving 5 s of SUMO time after the controller detached.
#
# Usage: scripts/bench_outside_stops.sh [BUILD_DIR] [SEEDS] [OUT_DIR]
#   BUILD_DIR  where rtlacam-sumo was built (default: build)
#   SEEDS      runs with stops per net and executor (default: 3)
#   OUT_DIR    default: out/bench_outside_stops
# Expected: exit 0, 0 collisions, max decel <= the vType's, 0 moving after 5 s in every run.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="$(cd "${1:-$ROOT/build}" && pwd)"
SEEDS="${2:-3}"
OUT="${3:-$ROOT/out/bench_outside_stops}"
APP="$BUILD/apps/rtlacam-sumo"
CLIENT="$ROOT/scripts/traci_second_client.py"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
[ -x "$APP" ] || { echo "bench_outside_stops: $APP not built (cmake --build $BUILD --target rtlacam-sumo)" >&2; exit 1; }
mkdir -p "$OUT"
OUT="$(cd "$OUT" && pwd)"
SC="$ROOT/sumo_scenarios"

free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1]); s.close()'; }

# name -> net, additional, cell length, AGV length, min gap, AGVs
yaml() {  # name executor -> a run config on stdout
  local name="$1" ex="$2" net add cell=1.0 len=0.8 gap=0.1 n=16
  case "$name" in
    small) net="$SC/small.net.xml"; add="$SC/small.add.xml" ;;
    tree) net="$SC/tree.net.xml"; add=""; n=10 ;;
    long) net="$SC/small.net.xml"; add="$SC/small.add.xml"; cell=2.0; len=1.6; gap=0.2; n=10 ;;
    tolgrid) net="$ROOT/tests/data/controller/tolgrid.net.xml"; add=""; n=12 ;;
  esac
  cat <<EOF
sumo:
  net: $net
$( [ -n "$add" ] && echo "  additional: $add" || true )
  step_length: 0.125
  outputs: {fcd: true, tripinfo: false, summary: false, collision: true}
  extra_args: ["--precision", "6"]
grid: {cell_length: $cell}
fleet:
  count: $n
  seed: 1
  starts: random
  vtype: {length: $len, width: 0.6, min_gap: $gap, accel: 0.5, decel: 1.0, max_speed: 1.0}
planner: {solver: rtlacam, budget_ms: 1.0, seed: 0}
tasks: {mode: one_shot, goals: random, seed: 2}
run: {tick_s: 1.0, max_ticks: 1000, executor: $ex, window: 4, progress_s: 0}
EOF
}

one() {  # name executor seed share -> one TSV row
  local name="$1" ex="$2" seed="$3" share="$4"
  local dir="$OUT/$name/$ex/s$seed"
  rm -rf "$dir"; mkdir -p "$dir"
  yaml "$name" "$ex" > "$dir/run.yaml"
  local net port
  net="$(sed -n 's/^  net: //p' "$dir/run.yaml")"
  port="$(free_port)"
  sumo -n "$net" --remote-port "$port" --num-clients 2 > "$dir/sumo.log" 2>&1 &
  local sumo_pid=$!
  python3 "$CLIENT" --port "$port" --order 2 --stop-share "$share" --stop-s 1 5 --decel 1.0 --seed "$seed" \
    --detached "$dir/detached" --report "$dir/second.json" --after-s 5 > "$dir/second.log" 2>&1 &
  local client_pid=$!
  local rc=0
  "$APP" "$dir/run.yaml" --port "$port" --order 1 --out "$dir" > "$dir/controller.log" 2>&1 || rc=$?
  python3 - "$dir" <<'EOF' > "$dir/detached.tmp"
import json, sys
m = json.load(open(sys.argv[1] + "/metrics.json"))
print(m["sim_s"] + m["executor"]["end_stop_steps"] * m["step_length"])
EOF
  mv "$dir/detached.tmp" "$dir/detached"
  wait "$client_pid" || true
  wait "$sumo_pid" || true
  python3 - "$dir" "$name" "$ex" "$seed" "$share" "$rc" <<'EOF'
import json, re, sys
d, name, ex, seed, share, rc = sys.argv[1:]
m = json.load(open(d + "/metrics.json"))
r = json.load(open(d + "/second.json"))
# fcd: per vehicle, speed change between consecutive timesteps
dt = m["step_length"]; prev = {}; t = None; acc = dec = 0.0
for line in open(d + "/fcd.xml"):
    s = re.search(r'<timestep time="([-0-9.e]+)"', line)
    if s:
        t = float(s.group(1)); continue
    v = re.search(r'<vehicle id="([^"]+)"[^>]* speed="([-0-9.e]+)"', line)
    if v and t is not None:
        i, sp = v.group(1), float(v.group(2))
        if i in prev and abs(t - prev[i][0] - dt) < 1e-6:
            acc = max(acc, (sp - prev[i][1]) / dt); dec = max(dec, (prev[i][1] - sp) / dt)
        prev[i] = (t, sp)
col = len(re.findall(r"<collision ", open(d + "/collision.xml").read())) if m.get("sim_s") else -1
print("\t".join(str(x) for x in [name, ex, seed, share, rc, m["error"].replace("\t", " ")[:80] or "-", int(m["solved"]),
      m["makespan"], round(m["bound_ticks"], 2), round(m["makespan_over_bound"], 3), r["steps_held"], r["collisions"], col,
      round(dec, 4), round(acc, 4), r["moving_at_check"], r["present_at_check"], r["present_at_detach"]]))
EOF
}

HEAD="net\texecutor\tseed\tstop_share\texit\terror\tsolved\tmakespan\tbound\tmakespan/bound\theld_steps\tcollision_steps\tcollision_xml\tmax_decel_fcd\tmax_accel_fcd\tmoving_5s_after\tpresent_5s_after\tpresent_at_detach"
printf "%b\n" "$HEAD" > "$OUT/runs.tsv"
for name in ${NETS:-small tree long tolgrid}; do
  for ex in adg-follow adg; do
    one "$name" "$ex" 0 0 >> "$OUT/runs.tsv"  # baseline: no outside stops
    for ((s = 1; s <= SEEDS; ++s)); do one "$name" "$ex" "$s" 0.1 >> "$OUT/runs.tsv"; done
    tail -n $((SEEDS + 1)) "$OUT/runs.tsv" >&2
  done
done
python3 - "$OUT/runs.tsv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1]), delimiter="\t"))
base = {(r["net"], r["executor"]): float(r["makespan"]) for r in rows if r["seed"] == "0"}
print("net        executor    runs aborts collisions max_decel(vType 1.0) moving_5s  makespan/bound  makespan/baseline")
for key in base:
    rs = [r for r in rows if (r["net"], r["executor"]) == key and r["seed"] != "0"]
    if not rs: continue
    aborts = sum(r["exit"] != "0" or r["error"] != "-" for r in rs)
    col = sum(int(r["collision_steps"]) + max(0, int(r["collision_xml"])) for r in rs)
    dec = max(float(r["max_decel_fcd"]) for r in rs)
    mov = sum(int(r["moving_5s_after"]) for r in rs)
    mb = sum(float(r["makespan/bound"]) for r in rs) / len(rs)
    rel = sum(float(r["makespan"]) for r in rs) / len(rs) / base[key]
    b = [r for r in rows if (r["net"], r["executor"]) == key and r["seed"] == "0"][0]
    print(f"{key[0]:10s} {key[1]:11s} {len(rs):4d} {aborts:6d} {col:10d} {dec:20.4f} {mov:9d}  {mb:6.3f} (base {float(b['makespan/bound']):.3f})  {rel:6.3f}")
EOF
