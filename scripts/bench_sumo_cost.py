#!/usr/bin/env python3
"""Where a SUMO tick's time goes, with two builds (before / after a change), same decisions.

One bench_twin.py SUMO row (the config with the physical vType, the solver, adg-follow, a
fixed number of expansions per SUMO step: deterministic decisions) run by each rtlacam-sumo
in turn, the same ticks. Prints per build the wall, control, planner and SUMO ms per tick
and the set_angle calls, then the after/before ratios, and whether both made the same
decisions (sum of costs, commands sent, errands finished). Exit 1 where they differ.

    scripts/bench_sumo_cost.py BEFORE/apps/rtlacam-sumo AFTER/apps/rtlacam-sumo \\
        [--config config/huge_warehouse_lifelong.yaml] [--solver pibt-rot+arrows] [--ticks 40] [--p 0]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_twin  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description="SUMO ms per tick with two builds, same decisions")
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--config", default="config/huge_warehouse_lifelong.yaml")
    ap.add_argument("--solver", default="pibt-rot+arrows", help="as bench_twin.py --solvers (one)")
    ap.add_argument("--ticks", type=int, default=40)
    ap.add_argument("--p", type=float, default=0.0)
    ap.add_argument("--expansions", type=int, default=5, help="planner expansions per SUMO step")
    ap.add_argument("--executor", default="adg-follow", choices=["lockstep", "adg", "adg-follow"])
    ap.add_argument("--out", help="keep runs here (default: a temporary folder)")
    a = ap.parse_args()
    for app in (a.before, a.after):
        if not os.access(app, os.X_OK):
            sys.exit(f"bench_sumo_cost.py: {app} is not an executable")
    work = os.path.abspath(a.out) if a.out else tempfile.mkdtemp(prefix="bench_sumo_cost_")
    os.makedirs(work, exist_ok=True)
    print(f"# {a.config}, {a.solver}, p {a.p:g}, {a.executor}, {a.ticks} ticks, {a.expansions} expansions per SUMO step; "
          f"files in {work}", flush=True)
    m = {}
    for name, app in (("before", a.before), ("after", a.after)):
        out = os.path.join(work, name)
        cfg = bench_twin.sumo_config(a.config, a.solver, a.p, out, a.ticks, a.expansions, a.executor)
        r = subprocess.run([os.path.abspath(app), cfg], capture_output=True, text=True)
        if not os.path.exists(os.path.join(out, "metrics.json")):
            sys.exit(f"bench_sumo_cost.py: {name}: rtlacam-sumo exit {r.returncode}: {r.stderr.strip().splitlines()[-1:]}")
        j = json.load(open(os.path.join(out, "metrics.json")))
        m[name] = j
        t = max(1, j["ticks"])
        print(f"{name}: {j['ticks']} ticks, wall {1000 * j['wall_s'] / t:.1f} ms/tick (setup included), control "
              f"{j['control_ms_per_tick']['mean']:.1f} (p50 {j['control_ms_per_tick']['p50']:.1f}), planner "
              f"{j['planner_ms_per_tick']['mean']:.2f}, SUMO {j['sumo_ms_per_step']['mean'] * j['sumo_ms_per_step']['count'] / t:.1f} "
              f"ms/tick; set_angle {j['commands']['set_angle']}; errands {j['lifelong'].get('numErrandFinished', '-')}, "
              f"error '{j['error']}'", flush=True)
    b, f = m["before"], m["after"]
    ratio = lambda k: f[k]["mean"] / b[k]["mean"] if b[k]["mean"] > 0 else float("nan")
    print(f"after / before: wall {f['wall_s'] / b['wall_s']:.3f}, control {ratio('control_ms_per_tick'):.3f}, "
          f"planner {ratio('planner_ms_per_tick'):.3f}, SUMO {ratio('sumo_ms_per_step'):.3f}")
    same = (b["soc"] == f["soc"] and b["commands"] == f["commands"] and b["ticks"] == f["ticks"] and
            b["lifelong"].get("numErrandFinished") == f["lifelong"].get("numErrandFinished"))
    print("same decisions (ticks, sum of costs, commands, errands):", "yes" if same else "NO")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
