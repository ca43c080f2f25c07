#!/usr/bin/env python3
"""Lifelong throughput with batteries and charging errands (issue 24; tasks/battery.hpp).

Runs of rtlacam-sumo on config/small_charging_lifelong.yaml in the same invocation,
identical but for the battery: none (no fleet.battery: the baseline), charging (the config's
battery, AGVs charge below the threshold between tasks and, below fleet.battery.critical or
the distance-aware reserve, mid-task), charging without the reserve (reserve_margin: 0),
charging without rematched claims (rematch: false), charging without the critical level, the
reserve and the rematch, charging without the planner priority of low AGVs
(tasks.urgency.battery: false; tasks/urgency.hpp), drain only
(fleet.battery.charging: false: the same drain, no charging errands).
--per-m-wh / --critical override the config's drain and critical level (aggressive
settings: --per-m-wh 1.5 --critical 0.25); --seeds runs every variant once per fleet.seed
(random starts). K: the longest stall of a busy AGV's errand (tasks/errand_stalls.hpp). The planner has a fixed number of expansions per SUMO step
(deterministic decisions). Prints errands per tick and the ratio to the baseline, the
charging errands, the charging share of AGV-ticks, the lowest charge and the AGVs that ran
empty; every run must end clean (0 violations, 0 jumps / re-syncs; the script says so), and
with charging no AGV may run empty.

  scripts/bench_charging.py [--build build] [--ticks 1000] [--expansions 50] [--agvs 16]
                            [--per-m-wh X] [--critical X] [--seeds 1,2,3,4] [--quick]
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


def run(build, out, ticks, expansions, agvs, battery, seed=None, urgency=None):
    cfg = yaml.safe_load(open(os.path.join(ROOT, BASE)))
    here = os.path.dirname(os.path.join(ROOT, BASE))
    for k in ("net", "additional"):
        cfg["sumo"][k] = os.path.normpath(os.path.join(here, cfg["sumo"][k]))
    cfg["sumo"]["outputs"] = {"fcd": False, "tripinfo": False, "summary": False, "collision": True}
    cfg["planner"]["budget_ms"] = 0
    cfg["planner"]["expansions"] = expansions
    cfg["fleet"]["count"] = agvs
    if seed is not None:
        cfg["fleet"]["seed"] = seed
    if battery is None:
        del cfg["fleet"]["battery"]
    else:
        cfg["fleet"]["battery"] = battery
    cfg["run"]["max_ticks"] = ticks
    if urgency is not None:
        cfg["tasks"]["urgency"] = urgency
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
    ap.add_argument("--per-m-wh", type=float)
    ap.add_argument("--critical", type=float)
    ap.add_argument("--quick", action="store_true", help="only no battery, charging, and charging with the battery priority off")
    ap.add_argument("--seeds", default="", help="comma-separated fleet.seed values (default: the config's)")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    tmp = tempfile.mkdtemp(prefix="bench_charging_")
    shipped = yaml.safe_load(open(os.path.join(ROOT, BASE)))["fleet"]["battery"]
    if a.per_m_wh is not None:
        shipped["per_m_wh"] = a.per_m_wh
    if a.critical is not None:
        shipped["critical"] = a.critical
    # The task layer's priority hints (tasks/urgency.hpp) are on unless a variant says otherwise.
    no_hint = {"battery": False}
    variants = [("no battery", None), ("charging", dict(shipped)),
                ("charging, battery priority off", dict(shipped), no_hint),
                ("charging, rematch off", dict(shipped, rematch=False)),
                ("charging, reserve off", dict(shipped, reserve_margin=0)),
                ("charging, critical, reserve and rematch off", dict(shipped, critical=0, reserve_margin=0, rematch=False)),
                ("drain only", dict(shipped, charging=False))]
    variants = [v if len(v) == 3 else (v[0], v[1], None) for v in variants]
    if a.quick:
        variants = variants[:3]
    seeds = [int(x) for x in a.seeds.split(",") if x] or [None]
    print(f"# {BASE}, {a.agvs} AGVs, {a.ticks} ticks, {a.expansions} expansions per SUMO step; battery {shipped}; "
          f"fleet seeds {a.seeds or 'the config'}")
    print("| seed | battery | errands/tick | vs no battery | charging errands | dropped mid-task | charging share | min charge | ran empty | K (stall max / p99) | errand ticks max | violations | jumps+resyncs |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    clean = True
    for seed in seeds:
        base = None
        for label, battery, urgency in variants:
            out = os.path.join(tmp, f"{seed}_" + label.replace(" ", "_").replace(",", ""))
            m = run(build, out, a.ticks, a.expansions, a.agvs, battery, seed, urgency)
            rate = m["lifelong"]["errandThroughput"]
            base = rate if base is None else base
            b = m.get("battery", {})
            jr = m["teleports_or_jumps"]
            clean = clean and m["violations"] == 0 and jr == 0 and m.get("collisions", 0) == 0 and not m["error"]
            if label == "charging":
                clean = clean and b["ran_empty"] == 0
            l = m["lifelong"]
            print(f"| {seed if seed is not None else '-'} | {label} | {rate:.3f} | {rate / base if base else 0:.2f} | "
                  f"{b.get('charging_errands', '-')} | {b.get('dropped_mid_task', '-')} | {b.get('charging_share', 0):.3f} | "
                  f"{b.get('min_charge', 1):.3f} | {b.get('ran_empty', '-')} | {l['stallTicks']['max']} / {l['stallTicks']['p99']} | "
                  f"{l['errandTicks']['max']} | {m['violations']} | {jr} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error; none ran empty with charging)" if clean
          else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


if __name__ == "__main__":
    sys.exit(main())
