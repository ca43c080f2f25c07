#!/usr/bin/env python3
"""Closed-loop executors against the physical bound (issue 21).

For each scenario config and delay probability p (Bernoulli per AGV per tick, stops of 1-5 s)
runs lockstep, adg and adg-follow (physics of the config) and prints makespan (one-shot) or
tasks per tick (lifelong), the physical bound (metrics.json bound_ticks: every AGV alone on its
planned path; lockstep: in moves) and their ratio, plus errors / collisions / overshoot.
A config without a fleet.vtype (the lifelong ones) gets the *_agv configs' kinematics.

Then, per row, the ratio over lockstep's at the same p and over the same executor's at p = 0.

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


# The AGV kinematics of the shipped *_agv configs, for a config without a vtype (the
# lifelong ones): the physical executors and the bound then use the same physics.
AGV_VTYPE = "  vtype: {length: 0.8, width: 0.6, min_gap: 0.1, accel: 0.5, decel: 1.0, max_speed: 1.0}\n"


def with_agv_vtype(path):
    s = open(path).read()
    if "vtype:" not in s:
        open(path, "w").write(s.replace("fleet:\n", "fleet:\n" + AGV_VTYPE, 1))


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
    ratio_of = {}  # (config, p, executor) -> makespan/bound (one-shot) or throughput/bound (lifelong)
    print("| config | p | executor | makespan or tasks/tick | bound | ratio | solved | error | overshoot m | wall s |")
    print("|---|---:|---|---:|---:|---:|---|---|---:|---:|")
    for c in a.configs:
        for p in a.ps:
            for ex in a.executors:
                cfg = yaml_variant(c, ex, p, window=a.window, max_ticks=a.max_ticks)
                with_agv_vtype(cfg)
                m = sumo_run(a.build, cfg, os.path.join(tmp, f"{c}_{ex}_{p}"))
                life = m.get("lifelong")
                if life:
                    val, bound, ratio = life["throughput"], life["throughputBound"], life["throughputOverBound"]
                else:
                    val, bound, ratio = m["makespan"], m["bound_ticks"], m["makespan_over_bound"]
                # an unfinished one-shot run has no makespan to compare
                ratio_of[(c, p, ex)] = (ratio if life or m["solved"] else None, bool(life))
                print(f"| {c} | {p} | {ex} | {val:.4g} | {bound:.4g} | {ratio:.3f} | {m['solved']} | "
                      f"{m['error'][:60]} | {m['executor'].get('overshoot_m', 0):.2g} | {m['_wall']:.1f} |", flush=True)
    # The targets (issue 21), against baselines of this run: at p = 0 the executor's ratio over
    # lockstep's (one-shot: makespan/bound, lower is better; lifelong: lockstep's
    # throughput/bound over the executor's, so > 1 is worse alike); at p > 0, the same
    # executor's ratio over its own at p = 0 (the same orientation).
    print("\n| config | p | executor | vs lockstep (same p) | vs itself at p = 0 |\n|---|---:|---|---:|---:|")
    for (c, p, ex), (r, life) in ratio_of.items():
        def rel(base):
            if base is None or r is None or base[0] is None or not r or not base[0]:
                return "-"
            return f"{(base[0] / r if life else r / base[0]):.3f}"
        print(f"| {c} | {p} | {ex} | {rel(ratio_of.get((c, p, 'lockstep')))} | {rel(ratio_of.get((c, 0.0, ex)))} |")


if __name__ == "__main__":
    main()
