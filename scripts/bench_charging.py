#!/usr/bin/env python3
"""Lifelong throughput with batteries and charging errands (issue 24; tasks/battery.hpp).

Four runs of rtlacam-sumo on config/small_charging_lifelong.yaml in the same invocation,
identical but for the battery: none (no fleet.battery: the baseline), charging (the config's
battery, AGVs charge below the threshold between tasks and, below fleet.battery.critical,
mid-task), charging without the critical level (critical: 0), drain only
(fleet.battery.charging: false: the same drain, no charging errands). The planner has a fixed number of expansions per SUMO step
(deterministic decisions). Prints errands per tick and the ratio to the baseline, the
charging errands, the charging share of AGV-ticks, the lowest charge and the AGVs that ran
empty; every run must end clean (0 violations, 0 jumps / re-syncs; the script says so), and
with charging no AGV may run empty.

  scripts/bench_charging.py [--build build] [--ticks 1000] [--expansions 50] [--agvs 16]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import yaml  # PyYAML

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = "config/small_charging_lifelong.yaml"


def run(build, out, ticks, expansions, agvs, battery):
    cfg = yaml.safe_load(open(os.path.join(ROOT, BASE)))
    here = os.path.dirname(os.path.join(ROOT, BASE))
    for k in ("net", "additional"):
        cfg["sumo"][k] = os.path.normpath(os.path.join(here, cfg["sumo"][k]))
    cfg["sumo"]["outputs"] = {"fcd": False, "tripinfo": False, "summary": False, "collision": True}
    cfg["planner"]["budget_ms"] = 0
    cfg["planner"]["expansions"] = expansions
    cfg["fleet"]["count"] = agvs
    if battery is None:
        del cfg["fleet"]["battery"]
    else:
        cfg["fleet"]["battery"] = battery
    cfg["run"]["max_ticks"] = ticks
    cfg["run"]["progress_s"] = 0
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
    ap.add_argument("--ticks", type=int, default=1000)
    ap.add_argument("--expansions", type=int, default=50)
    ap.add_argument("--agvs", type=int, default=16)
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    tmp = tempfile.mkdtemp(prefix="bench_charging_")
    shipped = yaml.safe_load(open(os.path.join(ROOT, BASE)))["fleet"]["battery"]
    variants = [("no battery", None), ("charging", dict(shipped)), ("charging, critical off", dict(shipped, critical=0)),
                ("drain only", dict(shipped, charging=False))]
    print(f"# {BASE}, {a.agvs} AGVs, {a.ticks} ticks, {a.expansions} expansions per SUMO step; battery {shipped}")
    print("| battery | errands/tick | vs no battery | charging errands | dropped mid-task | charging share | min charge | ran empty | max ticks on one errand | violations | jumps+resyncs |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    clean, base = True, None
    for label, battery in variants:
        m = run(build, os.path.join(tmp, label.replace(" ", "_").replace(",", "")), a.ticks, a.expansions, a.agvs, battery)
        rate = m["lifelong"]["errandThroughput"]
        base = rate if base is None else base
        b = m.get("battery", {})
        jr = m["teleports_or_jumps"]
        clean = clean and m["violations"] == 0 and jr == 0 and m.get("collisions", 0) == 0 and not m["error"]
        if label == "charging":
            clean = clean and b["ran_empty"] == 0
        print(f"| {label} | {rate:.3f} | {rate / base if base else 0:.2f} | {b.get('charging_errands', '-')} | "
              f"{b.get('dropped_mid_task', '-')} | {b.get('charging_share', 0):.3f} | {b.get('min_charge', 1):.3f} | "
              f"{b.get('ran_empty', '-')} | {m['lifelong']['maxErrandTicks']} | {m['violations']} | {jr} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error; none ran empty with charging)" if clean
          else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


if __name__ == "__main__":
    sys.exit(main())
