#!/usr/bin/env python3
"""Grid-twin sweeps of a SUMO lifelong config (docs/twin_bench.md, session 30).

The twin is the one bench_twin.py makes (rtlacam-gridify --map of the config's net, pick-up ->
drop tasks between its stations), and each row is one bench_twin.twin_run: rtlacam-lifelong
with a fixed number of expansions per step (deterministic), cell and rotation plans on the same
executor (--executor, default adg-follow) and delay model (--p, Bernoulli stops of 1-5 steps).
Session 30's sweep numbers ran the rotation rows synchronously (no executor): not comparable.
Two tables:
  --fleet 25,50,...   fleet sizes, for each of --solvers (no queues: the layout's own limit);
  default             each of --solvers at the config's fleet size, with the config's queues
                      and priorities.
Solvers as in bench_twin.py (SOLVER+arrows, +unguided, +distance, +age). Columns: errands per
step, over the first and the last --trend-window steps (1000), their ratio, the free-flow bound
and the share.

  scripts/bench_twin_sweep.py --config config/large_warehouse_queues.yaml \
      --solvers rtlacam,pibt,pibt-rot+unguided,pibt-rot,wppl,wppl+arrows,epibt [--steps 3000]
  scripts/bench_twin_sweep.py --config config/large_warehouse_lifelong.yaml --solvers rtlacam,pibt-rot+unguided \
      --fleet 25,50,100,150,200
"""
import argparse
import os
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
    ap.add_argument("--executor", default="adg-follow", choices=["lockstep", "adg", "adg-follow"])
    ap.add_argument("--p", type=float, default=0.0, help="Bernoulli stop probability per robot per step")
    ap.add_argument("--trend-window", type=int, default=1000, help="steps of the first and last windows")
    ap.add_argument("--out", help="keep runs here (default: a temporary folder)")
    a = ap.parse_args()
    a.build = os.path.abspath(a.build)
    if a.trend_window <= 0:
        sys.exit(f"bench_twin_sweep.py: --trend-window {a.trend_window}: must be positive")
    a.trend_window = min(a.trend_window, a.steps)  # a shorter run: both windows are the whole run
    work = os.path.abspath(a.out) if a.out else tempfile.mkdtemp(prefix="twin_sweep_")
    os.makedirs(work, exist_ok=True)
    twin = bench_twin.twin_problem(a, a.config, work)
    q = twin[1]
    sizes = [int(x) for x in a.fleet.split(",")] if a.fleet else [None]
    w = a.trend_window
    print(f"# twin of {a.config}, {a.steps} steps, {a.expansions} expansions per step, executor {a.executor}, "
          f"p {a.p:g}; files in {work}")
    print(f"| solver | AGVs | queues | errands/step | first {w} | last {w} | last/first | free-flow bound | share |")
    print("|---|---|---|---|---|---|---|---|---|", flush=True)
    for n in sizes:
        for name in a.solvers.split(","):
            t, err = bench_twin.twin_run(a.build, twin, name, a.p, os.path.join(work, f"{name}_{n or 'all'}"), a.steps,
                                         a.expansions, a.executor, agents=n)
            if err:
                print(f"# {name}: {err}", flush=True)
                continue
            first, last = bench_twin.windows(t["events"], t["steps"], w)
            print(f"| {name} | {n or t['team']} | {'off' if n or not q.get('capacity') else 'on'} | "
                  f"{t['thr']:.3f} | {first:.3f} | {last:.3f} | {last / first if first else 0:.2f} | "
                  f"{t['bound']:.3f} | {t['ratio']:.3f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
