#!/usr/bin/env python3
"""Where a SUMO tick's time goes, with two builds (before / after a change), same decisions.

One bench_twin.py SUMO row (the config with the physical vType, the solver, adg-follow, a
fixed number of expansions per SUMO step: deterministic decisions) run by each rtlacam-sumo
in turn, the same ticks, --rounds times (orders before-after, after-before, ...: a load
that drifts hits both alike). Prints per run the wall, control, planner and SUMO ms per
tick, the process's CPU ms per tick (user + sys, setup included: on a shared box wall
times grow with the load, CPU time less) and the SUMO calls sent; then per build the
median over the rounds and the after/before ratios of the medians; and whether every run
made the same decisions: ticks, sum of costs, errands finished and when (lifelong.json
events), quarter turns, turns in place, jumps, collisions, and the executed plan
(plan.txt, timing line aside) byte for byte. The number of SUMO calls is printed, not
compared: a change may send fewer calls for the same motion. --fcd also writes SUMO's fcd
output (x, y, angle, speed, lane, pos of every AGV every step) and compares it byte for
byte (header aside): what SUMO shows is the same too (slower: a check, not a timing).
Exit 1 where the decisions differ.

    scripts/bench_sumo_cost.py BEFORE/apps/rtlacam-sumo AFTER/apps/rtlacam-sumo \\
        [--config config/huge_warehouse_lifelong.yaml] [--solver pibt-rot+arrows] [--ticks 40] [--p 0] \\
        [--rounds 1] [--fcd]
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile

import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_twin  # noqa: E402


def decisions(path):
    """A run's file without what differs between two runs of the same decisions: plan.txt's
    timing line (comp_time), fcd.xml's header comment (date, output paths)."""
    data = open(path, "rb").read()
    if path.endswith(".xml"):
        k = data.find(b"<timestep")
        return data[k:] if k >= 0 else data
    return b"\n".join(line for line in data.split(b"\n") if not line.startswith(b"comp_time="))


def run(a, app, out):
    """One run; its per-tick numbers and what its decisions were."""
    cfg = bench_twin.sumo_config(a.config, a.solver, a.p, out, a.ticks, a.expansions, a.executor)
    if a.fcd:
        c = yaml.safe_load(open(cfg))
        c["sumo"]["outputs"]["fcd"] = True
        with open(cfg, "w") as f:
            yaml.safe_dump(c, f)
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run([os.path.abspath(app), cfg], capture_output=True, text=True)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if not os.path.exists(os.path.join(out, "metrics.json")):
        sys.exit(f"bench_sumo_cost.py: {out}: rtlacam-sumo exit {r.returncode}: {r.stderr.strip().splitlines()[-1:]}")
    j = json.load(open(os.path.join(out, "metrics.json")))
    t = max(1, j["ticks"])
    row = {"wall": 1000 * j["wall_s"] / t, "control": j["control_ms_per_tick"]["mean"],
           "planner": j["planner_ms_per_tick"]["mean"],
           "sumo": j["sumo_ms_per_step"]["mean"] * j["sumo_ms_per_step"]["count"] / t,
           "cpu": 1000 * ((r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)) / t}
    keys = ("ticks", "soc", "quarter_turns", "turns_in_place", "teleports_or_jumps", "collisions", "error")
    made = [j.get(k) for k in keys] + [j["lifelong"].get("numErrandFinished"),
                                       json.load(open(os.path.join(out, "lifelong.json")))["events"]]
    for name in ["plan.txt"] + (["fcd.xml"] if a.fcd else []):
        made.append(decisions(os.path.join(out, name)))
    c = j["commands"]
    print(f"{os.path.basename(out)}: {j['ticks']} ticks, wall {row['wall']:.1f} ms/tick (setup included), control "
          f"{row['control']:.1f} (p50 {j['control_ms_per_tick']['p50']:.1f}), planner {row['planner']:.2f}, "
          f"SUMO {row['sumo']:.1f} ms/tick; CPU {row['cpu']:.1f} ms/tick (setup included); set_angle {c['set_angle']}, "
          f"set_route {c['set_route']}, SUMO calls {c['total']}; errands {j['lifelong'].get('numErrandFinished', '-')}, "
          f"error '{j['error']}'", flush=True)
    return row, made


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
    ap.add_argument("--rounds", type=int, default=1, help="runs of each build, alternating their order")
    ap.add_argument("--fcd", action="store_true", help="also compare SUMO's fcd output byte for byte (slower)")
    ap.add_argument("--out", help="keep runs here (default: a temporary folder)")
    a = ap.parse_args()
    for app in (a.before, a.after):
        if not os.access(app, os.X_OK):
            sys.exit(f"bench_sumo_cost.py: {app} is not an executable")
    work = os.path.abspath(a.out) if a.out else tempfile.mkdtemp(prefix="bench_sumo_cost_")
    os.makedirs(work, exist_ok=True)
    print(f"# {a.config}, {a.solver}, p {a.p:g}, {a.executor}, {a.ticks} ticks, {a.expansions} expansions per SUMO step, "
          f"{a.rounds} round(s); files in {work}", flush=True)
    rows = {"before": [], "after": []}
    made = []
    for k in range(a.rounds):
        order = (("before", a.before), ("after", a.after))
        for name, app in (order if k % 2 == 0 else order[::-1]):
            row, m = run(a, app, os.path.join(work, f"{name}{k}"))
            rows[name].append(row)
            made.append(m)
    med = {n: {q: statistics.median(r[q] for r in rows[n]) for q in rows[n][0]} for n in rows}
    for n in ("before", "after"):
        print(f"{n} (median of {a.rounds}): " + ", ".join(f"{q} {v:.1f}" for q, v in med[n].items()) + " ms/tick")
    print("after / before: " + ", ".join(f"{q} {med['after'][q] / med['before'][q]:.3f}"
                                          for q in med["before"] if med["before"][q] > 0))
    same = all(m == made[0] for m in made)
    print("same decisions (ticks, soc, turns, jumps, collisions, error, errands and their ticks, plan.txt"
          f"{', fcd.xml' if a.fcd else ''}), every run:", "yes" if same else "NO")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
