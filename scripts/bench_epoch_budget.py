#!/usr/bin/env python3
"""Planner time per SUMO step at lifelong epoch starts (issue 21: p99 <= 1.2 x planner.budget_ms).

Runs a lifelong config (default huge_warehouse_lifelong.yaml: 1000 AGVs) with a time budget
(budget_ms, no expansion count), per executor, with run.epoch_in_budget off (the baseline:
the epoch start is set_goals plus a search slice of a whole budget, charged to the next step;
lockstep starts it at the tick's end) and on, interleaved (off, on, off, on, ...), and prints
metrics.json planner_cpu_ms_per_step (thread CPU time) p50 / p99 / max, p99 over the budget,
and on's p99 over off's from the same round. Errands per tick show what the search makes of it.

  scripts/bench_epoch_budget.py [--build build] [--config huge_warehouse_lifelong.yaml]
                                [--budget-ms 1.0] [--ticks 300] [--rounds 1]
                                [--executors lockstep adg-follow]
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


def timed_config(src, executor, budget_ms, ticks, run_keys="", planner_keys=""):
    """A temporary copy of config/SRC with a time budget only (budget_ms, no expansions), max_ticks
    and the executor; run_keys / planner_keys: YAML lines (two-space indented) added under run: /
    planner:. Also used by bench_prefetch.py."""
    s = open(os.path.join(ROOT, "config", src)).read()
    s = re.sub(r"budget_ms: [0-9.]+", f"budget_ms: {budget_ms}", s)
    s = re.sub(r"\n  expansions: \d+.*", "", s)  # a time budget only
    s = re.sub(r"max_ticks: \d+", f"max_ticks: {ticks}", s)
    s = re.sub(r"  executor: [\w-]+.*\n", "", s)
    s = s.replace("run:\n", f"run:\n  executor: {executor}\n{run_keys}", 1)
    if planner_keys:
        s = s.replace("planner:\n", f"planner:\n{planner_keys}", 1)
    f = tempfile.NamedTemporaryFile("w", suffix=".yaml", dir=os.path.join(ROOT, "config"), delete=False)
    f.write(s)
    f.close()
    with_agv_vtype(f.name)  # the *_agv kinematics for adg-follow (unused by lockstep)
    return f.name


def variant(src, executor, budget_ms, ticks, on):
    return timed_config(src, executor, budget_ms, ticks, run_keys=f"  epoch_in_budget: {'true' if on else 'false'}\n")


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
    ap.add_argument("--config", default="huge_warehouse_lifelong.yaml")
    ap.add_argument("--budget-ms", type=float, default=1.0)
    ap.add_argument("--ticks", type=int, default=300)
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--executors", nargs="+", default=["lockstep", "adg-follow"])
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="bench_epoch_")
    print(f"{a.config}, budget_ms {a.budget_ms}, {a.ticks} ticks; planner_cpu_ms_per_step (thread CPU), outputs in {tmp}")
    print("| round | executor | epoch_in_budget | p50 | p99 | max | p99 / budget | p99 on / off | epochs | errands/tick | error | wall s |")
    print("|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|")
    for r in range(a.rounds):
        for ex in a.executors:
            p99_off = None
            for on in (False, True):
                m = run(a.build, variant(a.config, ex, a.budget_ms, a.ticks, on), os.path.join(tmp, f"{r}_{ex}_{int(on)}"))
                c = m["planner_cpu_ms_per_step"]
                life = m.get("lifelong", {})
                ratio = f"{c['p99'] / p99_off:.3f}" if on and p99_off else "-"
                p99_off = c["p99"] if not on else p99_off
                print(f"| {r + 1} | {ex} | {'on' if on else 'off'} | {c['p50']:.3f} | {c['p99']:.3f} | {c['max']:.3f} | "
                      f"{c['p99'] / a.budget_ms:.3f} | {ratio} | {life.get('epochs', '-')} | "
                      f"{life.get('numErrandFinished', 0) / max(1, m['ticks']):.3f} | "
                      f"{m['error'][:50]} | {m['_wall']:.0f} |", flush=True)


if __name__ == "__main__":
    main()
