#!/usr/bin/env python3
"""Lane speeds in lockstep: lifelong throughput with the planner's lane costs off and on (issue 24).

A copy of a shipped lifelong config's net with some aisles slowed (lane `speed`, default:
aisle c1 of the small warehouse at 0.25 m/s, c2 at 0.5 m/s; the cells are 1 m, a tick 1 s,
so 1 m/s is a cell per tick), run by rtlacam-sumo in lockstep with run.lane_speeds on (a
step lasts the ticks its slowest move needs on its lane). In the same invocation, identical
but for the planner's lane costs (planner.lane_costs: slow cells cost ceil(v_fast / v_lane)
in the distance tables PIBT and LaCAM rank moves by):
  - off: the baseline (every move costs 1 in the tables);
  - on.
And, for reference, lane speeds off (the old behaviour: a cell per tick whatever the lane).
The planner has a fixed number of expansions per SUMO step (deterministic decisions).
Prints errands per tick, the ratio to the baseline, the ticks lockstep added for lane speeds
and the cells the costs made costlier; every run must end clean (0 violations, 0 jumps /
re-syncs, no error: the script says so).

  scripts/bench_lane_costs.py [--build build] [--config config/small_warehouse_lifelong.yaml]
      [--slow c1r0_c1r1=0.25,c2r0_c2r1=0.5] [--ticks 1000] [--expansions 50] [--agvs 16] [--executor lockstep]
      [--solver pibt-rot]
--solver: every run with this planner.solver (default: the config's); the rotation solvers read
the lane costs in their (cell, heading) tables (planner/rotation/rotation_dist.hpp).
With --executor adg | adg-follow the config's vType drives; lane speeds are then the Driver's
speed cap (off: it ignores the lanes' limits, the reference row).
A --slow entry names an edge; it and its reverse edge (B_A for A_B) get the speed.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

import yaml  # PyYAML

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def slow_net(src, dst, slow):
    """Writes src with the lanes of the named edges (and their reverses) at the given speeds."""
    speeds = {}
    for e, v in slow.items():
        speeds[e] = v
        a, b = e.split("_", 1)
        speeds[f"{b}_{a}"] = v
    text = open(src).read()
    done = set()

    def lane(m):
        edge = m.group(2)
        if edge not in speeds:
            return m.group(0)
        done.add(edge)
        return re.sub(r'speed="[0-9.]+"', f'speed="{speeds[edge]:.2f}"', m.group(0))

    text = re.sub(r'<lane id="(([^"]+)_\d+)"[^>]*>', lane, text)
    missing = sorted(set(speeds) - done)
    if missing:
        sys.exit(f"--slow: no lane of edge(s) {', '.join(missing)} in {src}")
    open(dst, "w").write(text)


def run(build, base, net, out, ticks, expansions, agvs, costs, speeds, executor, solver):
    cfg = yaml.safe_load(open(os.path.join(ROOT, base)))
    here = os.path.dirname(os.path.join(ROOT, base))
    cfg["sumo"]["additional"] = os.path.normpath(os.path.join(here, cfg["sumo"]["additional"]))
    cfg["sumo"]["net"] = net
    cfg["sumo"]["outputs"] = {"fcd": False, "tripinfo": False, "summary": False, "collision": True}
    cfg["planner"]["budget_ms"] = 0
    cfg["planner"]["expansions"] = expansions
    cfg["planner"]["lane_costs"] = costs
    if solver:
        cfg["planner"]["solver"] = solver
    cfg["fleet"]["count"] = agvs
    cfg["run"]["max_ticks"] = ticks
    cfg["run"]["progress_s"] = 0
    cfg["run"]["executor"] = executor
    cfg["run"]["lane_speeds"] = speeds
    cfg["output"] = {"dir": out, "congestion": False}
    path = out + ".yaml"
    with open(path, "w") as f:
        yaml.safe_dump(cfg, f)
    p = subprocess.run([os.path.join(build, "apps", "rtlacam-sumo"), path], capture_output=True, text=True)
    if p.returncode not in (0, 4):
        sys.exit(f"{path}: exit {p.returncode}: {p.stderr.strip()[-400:]}")
    return json.load(open(os.path.join(out, "metrics.json")))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--config", default="config/small_warehouse_lifelong.yaml")
    ap.add_argument("--slow", default="c1r0_c1r1=0.25,c2r0_c2r1=0.5")
    ap.add_argument("--ticks", type=int, default=1000)
    ap.add_argument("--expansions", type=int, default=50)
    ap.add_argument("--agvs", type=int, default=16)
    ap.add_argument("--executor", default="lockstep", help="lockstep | adg | adg-follow (the Driver caps speeds)")
    ap.add_argument("--solver", help="planner.solver (default: the config's)")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    slow = {e: float(v) for e, v in (kv.split("=") for kv in a.slow.split(","))}
    tmp = tempfile.mkdtemp(prefix="bench_lane_costs_")
    cfg = yaml.safe_load(open(os.path.join(ROOT, a.config)))
    src = os.path.normpath(os.path.join(os.path.dirname(os.path.join(ROOT, a.config)), cfg["sumo"]["net"]))
    net = os.path.join(tmp, "slow.net.xml")
    slow_net(src, net, slow)
    print(f"# {a.config}, slowed {a.slow}, {a.agvs} AGVs, {a.ticks} ticks, {a.executor}, solver {a.solver or cfg['planner']['solver']}, "
          f"{a.expansions} expansions per SUMO step")
    print("| lane speeds | lane costs | errands/tick | vs costs off | lane ticks | costly cells | violations | jumps+resyncs |")
    print("|---|---|---|---|---|---|---|---|")
    clean, base = True, None
    for speeds, costs in ((True, False), (True, True), (False, False)):
        label = f"{'on' if speeds else 'off'}_{'on' if costs else 'off'}"
        m = run(build, a.config, net, os.path.join(tmp, label), a.ticks, a.expansions, a.agvs, costs, speeds, a.executor, a.solver)
        rate = m["lifelong"]["errandThroughput"]
        base = rate if base is None else base
        ls = m.get("lane_speeds", {})
        jr = m["teleports_or_jumps"]
        clean = clean and m["violations"] == 0 and jr == 0 and not m["error"]
        print(f"| {'on' if speeds else 'off (reference)'} | {'on' if costs else 'off'} | {rate:.3f} | "
              f"{rate / base if base else 0:.2f} | {ls.get('lockstep_ticks', 0)} | {ls.get('costly_cells', 0)} | "
              f"{m['violations']} | {jr} |", flush=True)
    print("all runs clean (0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT CLEAN: see the table")
    sys.exit(0 if clean else 1)


if __name__ == "__main__":
    main()
