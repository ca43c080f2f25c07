#!/usr/bin/env python3
"""planner.prefetch in the SUMO controller (issue 20): the tables of the goals to come grown
before the run and in the SUMO steps' spare budget, as rtlacam-lifelong --prefetch does.

Runs a lifelong config with a time budget (budget_ms, no expansion count) per executor, with
planner.prefetch off (the baseline: the behaviour before issue 20) and on, interleaved (off,
on, off, on, ...), and prints errands per tick, on's over off's from the same round, the
epoch starts' distance reads answered with a lower bound (epochDistEstimates), the BFS work
done ahead (precomputePops) and metrics.json planner_cpu_ms_per_step p50 / p99.

  scripts/bench_prefetch.py [--build build] [--config large_warehouse_lifelong.yaml]
                            [--budget-ms 1.0] [--ticks 300] [--rounds 1] [--executors lockstep adg-follow]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_closed_loop import with_agv_vtype  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def variant(src, executor, budget_ms, ticks, on):
    s = open(os.path.join(ROOT, "config", src)).read()
    s = re.sub(r"budget_ms: [0-9.]+", f"budget_ms: {budget_ms}", s)
    s = re.sub(r"\n  expansions: \d+.*", "", s)  # a time budget only
    s = re.sub(r"max_ticks: \d+", f"max_ticks: {ticks}", s)
    s = re.sub(r"  executor: [\w-]+.*\n", "", s)
    s = s.replace("run:\n", f"run:\n  executor: {executor}\n", 1)
    s = s.replace("planner:\n", f"planner:\n  prefetch: {'true' if on else 'false'}\n", 1)
    f = tempfile.NamedTemporaryFile("w", suffix=".yaml", dir=os.path.join(ROOT, "config"), delete=False)
    f.write(s)
    f.close()
    with_agv_vtype(f.name)  # the *_agv kinematics for adg-follow (unused by lockstep)
    return f.name


def run(build, cfg, out):
    t0 = time.time()
    p = subprocess.run([os.path.join(build, "apps", "rtlacam-sumo"), cfg, "--out", out], capture_output=True, text=True)
    os.unlink(cfg)
    m = json.load(open(os.path.join(out, "metrics.json")))
    m["_wall"], m["_rc"] = time.time() - t0, p.returncode
    return m


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--config", default="large_warehouse_lifelong.yaml")
    ap.add_argument("--budget-ms", type=float, default=1.0)
    ap.add_argument("--ticks", type=int, default=300)
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--executors", nargs="+", default=["lockstep", "adg-follow"])
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="bench_prefetch_")
    print(f"{a.config}, budget_ms {a.budget_ms}, {a.ticks} ticks; outputs in {tmp}")
    print("| round | executor | prefetch | errands/tick | on / off | epochDistEstimates | precomputePops | "
          "cpu p50 ms | cpu p99 ms | epochs | error | wall s |")
    print("|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|")
    for r in range(a.rounds):
        for ex in a.executors:
            off = None
            for on in (False, True):
                m = run(a.build, variant(a.config, ex, a.budget_ms, a.ticks, on), os.path.join(tmp, f"{r}_{ex}_{int(on)}"))
                c = m["planner_cpu_ms_per_step"]
                life = m.get("lifelong", {})
                ept = life.get("numErrandFinished", 0) / max(1, m["ticks"])
                ratio = f"{ept / off:.3f}" if on and off else "-"
                off = ept if not on else off
                print(f"| {r + 1} | {ex} | {'on' if on else 'off'} | {ept:.3f} | {ratio} | {life.get('epochDistEstimates', '-')} | "
                      f"{life.get('precomputePops', '-')} | {c['p50']:.3f} | {c['p99']:.3f} | {life.get('epochs', '-')} | "
                      f"{m['error'][:50]} | {m['_wall']:.0f} |", flush=True)


if __name__ == "__main__":
    main()
