#!/usr/bin/env python3
"""Planner time per step, two builds interleaved (issue 20: one StepBudget for both lifelong
back ends; "behaviour unchanged" for timed runs means not worse).

SUMO: each config with a time budget only (planner.budget_ms, no expansion count), OLD and
NEW rtlacam-sumo alternating (old first in odd rounds, new first in even ones); prints
metrics.json planner_cpu_ms_per_step (thread CPU) p50 / p99 / max, searches skipped, and the
run's outcome. Grid: rtlacam-lifelong at the same budget (plannerTimeStats: wall,
plannerCpuTimeStats: CPU). Then per config the median over rounds of NEW / OLD for p99 and max.

  scripts/bench_step_budget.py --sumo OLD NEW --lifelong OLD NEW [--budget-ms 1] [--rounds 3]
                               [--ticks 300] [--configs small_warehouse_agv.yaml:adg-follow ...]
                               [--prefetch]   (planner.prefetch: true: the guard's runs)
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_epoch_budget import timed_config  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
LORR = os.path.join(HERE, "..", "..", "shared", "benchmarks", "lorr", "2023", "warehouse.domain", "MR23-I-06.json")

CONFIGS = ["small_warehouse_agv.yaml:adg-follow", "large_warehouse_agv.yaml:adg-follow",
           "huge_warehouse_lifelong.yaml:lockstep"]
# Grid runs: (name, arguments after the budget).
GRID = [("MR23-I-06 1000 rtlacam", ["--agents", "1000", "--solver", "rtlacam"]),
        ("MR23-I-06 1000 rtlacam skip-late", ["--agents", "1000", "--solver", "rtlacam", "--skip-late-search"])]


def sumo(binary, src, executor, budget_ms, ticks, out, prefetch=False):
    cfg = timed_config(src, executor, budget_ms, ticks, planner_keys="  prefetch: true\n" if prefetch else "")
    t0 = time.time()
    p = subprocess.run([binary, cfg, "--out", out], capture_output=True, text=True)
    os.unlink(cfg)
    m = json.load(open(os.path.join(out, "metrics.json")))
    c = m["planner_cpu_ms_per_step"]
    life = m.get("lifelong", {})
    what = (f"{life.get('numErrandFinished', 0) / max(1, m['ticks']):.3f} errands/tick" if life else
            f"makespan {m['makespan']}{'' if m['solved'] else ' (unsolved)'}")
    return {"p50": c["p50"], "p99": c["p99"], "max": c["max"], "skipped": m["executor"]["searches_skipped"],
            "what": what + (f", error {m['error'][:40]}" if m["error"] or p.returncode else ""), "wall": time.time() - t0}


def grid(binary, args, budget_ms, ticks):
    t0 = time.time()
    p = subprocess.run([binary, "--problem", LORR, "--steps", str(ticks), "--budget-ms", str(budget_ms)] + args,
                       capture_output=True, text=True)
    d = json.loads(p.stdout[p.stdout.index("{"):])
    w, c = d["plannerTimeStats"], d["plannerCpuTimeStats"]
    return {"p50": c["p50"], "p99": c["p99"], "max": c["max"], "wall_p99": w["p99"], "skipped": d["searchesSkipped"],
            "what": f"{d['errandThroughput']:.3f} errands/step", "wall": time.time() - t0}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sumo", nargs=2, metavar=("OLD", "NEW"))
    ap.add_argument("--lifelong", nargs=2, metavar=("OLD", "NEW"))
    ap.add_argument("--budget-ms", type=float, default=1.0)
    ap.add_argument("--ticks", type=int, default=300)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--configs", nargs="+", default=CONFIGS, help="config/NAME.yaml:executor")
    ap.add_argument("--prefetch", action="store_true", help="planner.prefetch: true in every SUMO run")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="bench_step_budget_")
    print(f"budget_ms {a.budget_ms}, {a.ticks} ticks, {a.rounds} rounds{', planner.prefetch' if a.prefetch else ''}; "
          f"planner CPU ms per step; outputs in {tmp}")
    print("| round | run | build | p50 | p99 | max | grid wall p99 | skipped | outcome | wall s |")
    print("|---:|---|---|---:|---:|---:|---:|---:|---|---:|")
    ratios = {}
    jobs = []
    if a.sumo:
        for c in a.configs:
            src, ex = c.split(":")
            jobs.append((src.replace(".yaml", "") + " " + ex, lambda b, r, o, src=src, ex=ex:
                         sumo(os.path.abspath(b), src, ex, a.budget_ms, a.ticks, os.path.join(tmp, f"{r}_{o}_{src}"),
                              a.prefetch), a.sumo))
    if a.lifelong:
        for name, args in GRID:
            jobs.append((name, lambda b, r, o, args=args: grid(os.path.abspath(b), args, a.budget_ms, a.ticks), a.lifelong))
    for r in range(a.rounds):
        for name, fn, (old, new) in jobs:
            order = [("old", old), ("new", new)] if r % 2 == 0 else [("new", new), ("old", old)]
            got = {}
            for tag, b in order:
                x = fn(b, r, tag)
                got[tag] = x
                print(f"| {r + 1} | {name} | {tag} | {x['p50']:.3f} | {x['p99']:.3f} | {x['max']:.3f} | "
                      f"{x.get('wall_p99', float('nan')):.3f} | {x['skipped']} | {x['what']} | {x['wall']:.0f} |", flush=True)
            ratios.setdefault(name, []).append((got["new"]["p99"] / got["old"]["p99"], got["new"]["max"] / got["old"]["max"]))
    print("\n| run | new / old p99 (median over rounds) | new / old max (median) | per round p99 |")
    print("|---|---:|---:|---|")
    for name, rs in ratios.items():
        print(f"| {name} | {statistics.median(x for x, _ in rs):.3f} | {statistics.median(y for _, y in rs):.3f} | "
              f"{', '.join(f'{x:.3f}' for x, _ in rs)} |")


if __name__ == "__main__":
    main()
