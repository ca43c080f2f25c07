#!/usr/bin/env python3
"""Closed-loop executors against the physical bound (issue 21).

For each scenario config and delay probability p (Bernoulli per AGV per tick, stops of 1-5 s)
runs lockstep, adg and adg-follow (physics of the config) and prints makespan (one-shot) or
tasks per tick (lifelong), the physical bound (metrics.json bound_ticks: every AGV alone on its
planned path; lockstep: in moves) and their ratio, plus errors / collisions / overshoot.

  scripts/bench_closed_loop.py [--build build] [--configs small_warehouse_agv.yaml ...]
                               [--ps 0 0.01] [--executors lockstep adg adg-follow] [--max-ticks N]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_executor import yaml_variant, sumo_run  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--configs", nargs="+", default=["small_warehouse_agv.yaml", "large_warehouse_agv.yaml"])
    ap.add_argument("--ps", nargs="+", type=float, default=[0, 0.01])
    ap.add_argument("--executors", nargs="+", default=["lockstep", "adg", "adg-follow"])
    ap.add_argument("--window", type=int, default=16)
    ap.add_argument("--max-ticks", type=int, default=None)
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="bench_closed_")
    print("| config | p | executor | makespan or tasks/tick | bound | ratio | solved | error | overshoot m | wall s |")
    print("|---|---:|---|---:|---:|---:|---|---|---:|---:|")
    for c in a.configs:
        for p in a.ps:
            for ex in a.executors:
                cfg = yaml_variant(c, ex, p, window=a.window, max_ticks=a.max_ticks)
                m = sumo_run(a.build, cfg, os.path.join(tmp, f"{c}_{ex}_{p}"))
                life = m.get("lifelong")
                if life:
                    val, bound, ratio = life["throughput"], life["throughputBound"], life["throughputOverBound"]
                else:
                    val, bound, ratio = m["makespan"], m["bound_ticks"], m["makespan_over_bound"]
                print(f"| {c} | {p} | {ex} | {val:.4g} | {bound:.4g} | {ratio:.3f} | {m['solved']} | "
                      f"{m['error'][:60]} | {m['executor'].get('overshoot_m', 0):.2g} | {m['_wall']:.1f} |", flush=True)


if __name__ == "__main__":
    main()
