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
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_epoch_budget import run, timed_config  # noqa: E402



def variant(src, executor, budget_ms, ticks, on):
    return timed_config(src, executor, budget_ms, ticks, planner_keys=f"  prefetch: {'true' if on else 'false'}\n")


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
