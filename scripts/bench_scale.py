#!/usr/bin/env python3
"""Robots vs latency in SUMO (issue 20): lifelong runs with physics on a generated warehouse
family, one fleet size per row, all in one invocation on one machine.

Each fleet of N AGVs gets its own member of the family (sumo_scenarios/make_warehouse.py
--family AISLES ROWS: 10 m picking aisles at a 4 m pitch, ROWS shelf rows, a pick-up stub
under every even aisle and a drop stub over every odd one), sized so that the density stays
that of the shipped huge warehouse (about 4.7 cells per AGV). The run is the shipped 1000-AGV
lifelong setup (pool tasks, station queues, keep_priorities) with the physical AGVs of the
*_agv configs (accel 0.5, decel 1.0 m/s^2, 1 m/s) driven by adg-follow, and a wall-clock
planner budget per SUMO step (default 1 ms), so latency is what a real deployment would see.

Columns: planner ms per tick (p50 / p99, wall), planner CPU ms per SUMO step (p99, against
the budget), executor (commands and checks) and SUMO ms per tick, real-time factor (simulated
/ wall seconds), peak RSS (GNU time), errands per tick, collisions, and where the wall time
per simulated second goes (planner / commands and checks / SUMO): the largest share is what
limits the fleet. Ratios are against the smallest fleet of the same run.

  scripts/bench_scale.py [--build build] [--fleets 10,100,1000,5000] [--ticks 300]
                         [--budget-ms 1] [--executor adg-follow] [--out DIR]
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import yaml  # PyYAML

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.environ.setdefault("SUMO_HOME", "/usr/share/sumo")  # netconvert validates against its schemas
CELLS_PER_AGV = 4.7  # the huge warehouse: 4680 cells, 1000 AGVs


def layout(n):
    """(aisles, rows) of the family member for n AGVs: rows ~ sqrt(n) / 5, aisles to fit."""
    rows = max(1, round(math.sqrt(n) / 5))
    per_aisle = 10 * rows + 4 * (rows + 1)  # its aisle cells plus its share of the cross aisles
    aisles = max(4, math.ceil(CELLS_PER_AGV * n / per_aisle))
    return aisles, rows


def make_net(work, name, aisles, rows):
    subprocess.run([sys.executable, os.path.join(ROOT, "sumo_scenarios", "make_warehouse.py"), "--family",
                    str(aisles), str(rows), "--name", name, "--out", work], check=True)
    base = os.path.join(work, name)
    # The options of sumo_scenarios/build.sh: lane length == node distance, turnarounds everywhere.
    subprocess.run(["netconvert", "-n", base + ".nod.xml", "-e", base + ".edg.xml", "-o", base + ".net.xml",
                    "--no-internal-links", "--no-turnarounds.geometry", "false", "--default.junctions.radius", "0",
                    "--junctions.corner-detail", "0", "--offset.disable-normalization", "--no-warnings"],
                   check=True, stdout=subprocess.DEVNULL)
    return base + ".net.xml", base + ".add.xml"


def config(net, add, n, a, out):
    return {
        "sumo": {"net": net, "additional": add, "step_length": 0.125,
                 "outputs": {"fcd": False, "tripinfo": False, "summary": False, "collision": True}},
        "grid": {"cell_length": 1.0},
        "fleet": {"count": n, "seed": 1, "starts": "random",
                  "vtype": {"length": 0.8, "width": 0.6, "min_gap": 0.1, "accel": 0.5, "decel": 1.0,
                            "max_speed": 1.0}},
        "planner": {"solver": a.solver, "budget_ms": a.budget_ms, "keep_priorities": True},
        "tasks": {"mode": "lifelong", "seed": 3, "random": {"count": 1000000, "errands": 2},
                  "assignment": "pool", "assigner": "greedy", "queues": {"capacity": 1, "length": 8}},
        "run": {"executor": a.executor, "window": 16, "tick_s": 1.0, "max_ticks": a.ticks, "backend": "libsumo",
                "progress_s": 0},
        "output": {"dir": out, "congestion": False},
    }


def main():
    ap = argparse.ArgumentParser(description="robots vs latency in SUMO (lifelong, physics)")
    ap.add_argument("--build", default="build")
    ap.add_argument("--fleets", default="10,100,1000,5000", help="fleet sizes, comma-separated")
    ap.add_argument("--ticks", type=int, default=300, help="ticks (1 s each) per run")
    ap.add_argument("--budget-ms", type=float, default=1.0, help="planner budget per SUMO step (wall clock)")
    ap.add_argument("--executor", default="adg-follow", choices=["lockstep", "adg", "adg-follow"])
    ap.add_argument("--solver", default="rtlacam")
    ap.add_argument("--out", help="keep nets, configs and outputs here (default: a temporary folder)")
    a = ap.parse_args()
    sumo = os.path.join(os.path.abspath(a.build), "apps", "rtlacam-sumo")
    if not os.access(sumo, os.X_OK):
        sys.exit(f"bench_scale.py: {sumo} is not built (cmake --build {a.build} --target rtlacam-sumo)")
    if not shutil.which("netconvert") or not os.access("/usr/bin/time", os.X_OK):
        sys.exit("bench_scale.py: needs netconvert (sumo) and GNU time (/usr/bin/time)")
    try:
        fleets = [int(x) for x in a.fleets.split(",")]
    except ValueError:
        sys.exit(f"bench_scale.py: --fleets: '{a.fleets}' is not a comma-separated list of integers")
    work = os.path.abspath(a.out) if a.out else tempfile.mkdtemp(prefix="bench_scale_")
    os.makedirs(work, exist_ok=True)
    print(f"# bench_scale.py: {a.solver}, {a.executor}, budget {a.budget_ms} ms per SUMO step, {a.ticks} ticks; "
          f"load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; files in {work}", flush=True)
    rows, clean = [], True
    for n in fleets:
        aisles, shelf_rows = layout(n)
        name = f"w{aisles}x{shelf_rows}"
        net, add = make_net(work, name, aisles, shelf_rows)
        out = os.path.join(work, f"n{n}")
        path = out + ".yaml"
        with open(path, "w") as f:
            yaml.safe_dump(config(net, add, n, a, out), f)
        rss = os.path.join(work, f"n{n}.rss")
        p = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", rss, sumo, path], capture_output=True, text=True)
        mpath = os.path.join(out, "metrics.json")
        if p.returncode != 0 or not os.path.exists(mpath):
            print(f"# N={n}: rtlacam-sumo exit {p.returncode}: {p.stderr.strip().splitlines()[-1:]}", flush=True)
            clean = False
            continue
        m = json.load(open(mpath))
        ll = m["lifelong"]
        steps_per_tick = m["tick_s"] / m["step_length"]
        share = m["ms_per_sim_s"]
        rows.append({
            "n": n, "net": name, "cells": m["cells"], "ticks": m["ticks"],
            "plan_p50": m["planner_ms_per_tick"]["p50"], "plan_p99": m["planner_ms_per_tick"]["p99"],
            "cpu_p99": m["planner_cpu_ms_per_step"]["p99"],
            "exec": m["control_ms_per_tick"]["mean"],
            "sumo": m["sumo_ms_per_step"]["mean"] * steps_per_tick,
            "rtf": m["real_time_factor"], "rss": int(open(rss).read().split()[-1]) / 1024.0,
            "thr": ll["errandThroughput"], "coll": m["collisions"], "jumps": m["commands"]["jumps"],
            "viol": m["violations"],
            "split": (share["planner"], share["control"], share["sumo"]),
        })
        r = rows[-1]
        clean &= r["coll"] == 0 and r["jumps"] == 0 and r["viol"] == 0
        print(f"# N={n}: {name} ({r['cells']} cells), {r['ticks']} ticks, wall {m['wall_s']:.0f} s", flush=True)
    if not rows:
        sys.exit("bench_scale.py: no run finished")
    b = rows[0]
    print()
    print("| AGVs | net (aisles x rows) | cells | planner ms/tick p50 / p99 | planner CPU ms/step p99 (budget "
          f"{a.budget_ms:g}) | executor ms/tick | SUMO ms/tick | real-time factor | peak RSS MB | errands/tick "
          "| collisions | wall per sim s: planner / executor / SUMO | ms per AGV-tick vs " + str(b["n"]) + " AGVs |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        total = sum(r["split"])
        per_agv = (r["plan_p50"] + r["exec"] + r["sumo"]) / r["n"]
        per_agv0 = (b["plan_p50"] + b["exec"] + b["sumo"]) / b["n"]
        print(f"| {r['n']} | {r['net']} | {r['cells']} | {r['plan_p50']:.2f} / {r['plan_p99']:.2f} | {r['cpu_p99']:.3f} "
              f"| {r['exec']:.2f} | {r['sumo']:.2f} | {r['rtf']:.2f} | {r['rss']:.0f} | {r['thr']:.3f} | {r['coll']} "
              f"| {100 * r['split'][0] / total:.0f} % / {100 * r['split'][1] / total:.0f} % / "
              f"{100 * r['split'][2] / total:.0f} % | {per_agv / per_agv0:.2f} |")
    print()
    print("all runs clean (0 collisions, 0 jumps, 0 violations)" if clean else "NOT CLEAN: see the lines above")
    return 0 if clean else 1


if __name__ == "__main__":
    sys.exit(main())
