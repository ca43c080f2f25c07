#!/usr/bin/env python3
"""Grid-twin sweeps of a SUMO lifelong config (docs/twin_bench.md, session 30).

The twin is the one bench_twin.py makes (rtlacam-gridify --map of the config's net, pick-up ->
drop tasks between its stations). Two tables, each row one rtlacam-lifelong run with a fixed
number of expansions per step (deterministic):
  --fleet 25,50,...   fleet sizes, for each of --solvers (no queues: the layout's own limit);
  default             each of --solvers at the config's fleet size, with the config's queues
                      and priorities.
Solvers as in bench_twin.py (SOLVER+arrows, +unguided, +distance, +age). Columns: errands per
step, over steps 1-1000 and the last 1000, their ratio, the free-flow bound and the share.

  scripts/bench_twin_sweep.py --config config/large_warehouse_queues.yaml \
      --solvers rtlacam,pibt,pibt-rot+unguided,pibt-rot,wppl,wppl+arrows,epibt [--steps 3000]
  scripts/bench_twin_sweep.py --config config/large_warehouse_lifelong.yaml --solvers rtlacam,pibt-rot+unguided \
      --fleet 25,50,100,150,200
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
    ap = argparse.ArgumentParser(description="grid-twin sweeps of a SUMO lifelong config")
    ap.add_argument("--build", default="build")
    ap.add_argument("--config", required=True)
    ap.add_argument("--solvers", default="rtlacam,pibt-rot")
    ap.add_argument("--fleet", help="comma-separated fleet sizes (queues off)")
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--expansions", type=int, default=40, help="per grid step")
    ap.add_argument("--out", help="keep runs here (default: a temporary folder)")
    a = ap.parse_args()
    a.build = os.path.abspath(a.build)
    work = os.path.abspath(a.out) if a.out else tempfile.mkdtemp(prefix="twin_sweep_")
    os.makedirs(work, exist_ok=True)
    prob, q, keep, _ = bench_twin.twin_problem(a, a.config, work)
    sizes = [int(x) for x in a.fleet.split(",")] if a.fleet else [None]
    print(f"# twin of {a.config}, {a.steps} steps, {a.expansions} expansions per step; files in {work}")
    print("| solver | AGVs | queues | errands/step | first 1000 | last 1000 | last/first | free-flow bound | share |")
    print("|---|---|---|---|---|---|---|---|---|", flush=True)
    for n in sizes:
        for name in a.solvers.split(","):
            solver, rot = bench_twin.variant(name)
            out = os.path.join(work, f"{name}_{n or 'all'}.json")
            cmd = [os.path.join(a.build, "apps", "rtlacam-lifelong"), "--problem", prob, "--steps", str(a.steps),
                   "--budget-ms", "1000", "--budget-expansions", str(a.expansions), "--solver", solver, "--quiet",
                   "--out", out]
            cmd += bench_twin.twin_rotation_args(solver, rot) if solver in bench_twin.ROTATION else ["--executor", "adg-follow"]
            if n:
                cmd += ["--agents", str(n)]
            elif q.get("capacity", 0) > 0:
                cmd += ["--queue-capacity", str(q["capacity"]), "--queue-length", str(q.get("length", 8))]
            if not keep or n:
                cmd.append("--reset-priorities")
            r = subprocess.run(cmd, capture_output=True, text=True)
            if r.returncode != 0:
                print(f"# {name}: rtlacam-lifelong exit {r.returncode}: {r.stderr.strip().splitlines()[-1:]}", flush=True)
                continue
            j = json.load(open(out))
            ev = [e[0] for e in j["events"]]
            first = sum(1 for t in ev if t <= 1000) / min(1000, a.steps)
            last = sum(1 for t in ev if t > a.steps - 1000) / min(1000, a.steps)
            bound = j.get("freeFlowBound", 0)
            print(f"| {name} | {n or j['teamSize']} | {'off' if n or not q.get('capacity') else 'on'} | "
                  f"{j['errandThroughput']:.3f} | {first:.3f} | {last:.3f} | {last / first if first else 0:.2f} | "
                  f"{bound:.3f} | {j['errandThroughput'] / bound if bound else 0:.3f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
