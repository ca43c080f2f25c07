#!/usr/bin/env python3
"""Same decisions before and after a refactor: deterministic rtlacam-lifelong runs
(--budget-expansions, a budget no step reaches) of every solver with two builds, LoRR logs
compared byte for byte once the timing fields are taken out.

    scripts/same_decisions.py BEFORE/apps/rtlacam-lifelong AFTER/apps/rtlacam-lifelong [--steps 150]

Prints one line per run (identical / DIFFERENT: the first differing key) and exits 1 on any
difference. The LoRR instances come from ../shared/benchmarks/lorr (see its README).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
LORR = os.path.join(HERE, "..", "..", "shared", "benchmarks", "lorr", "2023")
RANDOM = os.path.join(LORR, "random.domain", "MR23-I-03.json")
WAREHOUSE = os.path.join(LORR, "warehouse.domain", "MR23-I-06.json")

# (name, problem, extra arguments): every solver, both action models, both task modes.
RUNS = [
    ("rtlacam grid4", RANDOM, ["--solver", "rtlacam"]),
    ("rtlacam grid4 no-refine", RANDOM, ["--solver", "rtlacam", "--no-refine"]),
    ("naive grid4", RANDOM, ["--solver", "naive"]),
    ("pibt grid4", RANDOM, ["--solver", "pibt"]),
    ("rtlacam grid4 pool", RANDOM, ["--solver", "rtlacam", "--mode", "pool"]),
    ("rtlacam rotation", RANDOM, ["--solver", "rtlacam", "--action-model", "rotation"]),
    ("pibt-rot rotation", RANDOM, ["--solver", "pibt-rot", "--action-model", "rotation"]),
    ("epibt rotation", RANDOM, ["--solver", "epibt", "--action-model", "rotation"]),
    ("epibt rotation no-tf", RANDOM, ["--solver", "epibt", "--action-model", "rotation", "--traffic-flow", "off"]),
    ("wppl rotation", RANDOM, ["--solver", "wppl", "--action-model", "rotation"]),
    ("rtlacam adg delays", RANDOM, ["--solver", "rtlacam", "--executor", "adg", "--delay-kind", "bernoulli",
                                    "--delay-p", "0.05", "--delay-min", "1", "--delay-max", "5"]),
    ("rtlacam adg-follow delays", RANDOM, ["--solver", "rtlacam", "--executor", "adg-follow", "--delay-kind", "bernoulli",
                                           "--delay-p", "0.02"]),
    ("pibt lockstep delays", RANDOM, ["--solver", "pibt", "--executor", "lockstep", "--delay-kind", "bernoulli",
                                      "--delay-p", "0.02"]),
    ("rtlacam warehouse 300", WAREHOUSE, ["--solver", "rtlacam", "--agents", "300"]),
    ("epibt warehouse 300", WAREHOUSE, ["--solver", "epibt", "--action-model", "rotation", "--agents", "300"]),
]

# Task-layer runs (the one factory, tasks/task_layer.hpp) on the tests' 2024 RANDOM-01: cells
# of its agents file (agents 21..28, on nobody's start) as parking cells or chargers.
TESTS = os.path.join(HERE, "..", "tests", "data", "tasks", "lorr", "2024", "random.domain")
RANDOM24 = os.path.join(TESTS, "RANDOM-01.json")
CELLS = "@cells"  # an argument replaced by the path of that agents-format file
BATTERY = ["--battery-capacity-wh", "100", "--battery-initial", "0.5", "--battery-per-m-wh", "0.25",
           "--battery-threshold", "0.4", "--battery-critical", "0.25", "--battery-charge-w", "36000"]
RUNS += [
    ("pool queues urgency", RANDOM24, ["--solver", "rtlacam", "--agents", "40", "--mode", "pool", "--queue-capacity", "1",
                                       "--queue-length", "2", "--urgency"]),
    ("pool queues nearest pibt", RANDOM24, ["--solver", "pibt", "--agents", "40", "--mode", "pool", "--queue-capacity", "1",
                                            "--no-queue-fifo", "--queue-admission", "-1"]),
    ("hungarian parking", RANDOM24, ["--solver", "rtlacam", "--agents", "20", "--mode", "pool", "--assigner", "hungarian",
                                     "--k-nearest", "4", "--parking", CELLS]),
    ("battery chargers", RANDOM24, ["--solver", "rtlacam", "--agents", "20", "--chargers", CELLS] + BATTERY),
    ("battery no task check", RANDOM24, ["--solver", "rtlacam", "--agents", "20", "--chargers", CELLS,
                                         "--battery-no-task-check", "--battery-no-rematch"] + BATTERY),
]

# Log fields a newer build writes that an older one did not (compared when both have them):
# the task layer's counts (lifelong_epochs.hpp, issue 20).
NEW_KEYS = ("maxErrandTicks", "queues", "parking")


def cells_file(tmp):
    """Agents 21..28 of RANDOM-01's agents file, in the agents-file format."""
    lines = [l for l in open(os.path.join(TESTS, "agents", "random_32_32_20_100.agents")).read().split() if l]
    path = os.path.join(tmp, "cells.txt")
    with open(path, "w") as f:
        f.write("\n".join(["8"] + lines[22:30]) + "\n")
    return path


# Keys whose values are times (or counts of steps over a time budget): they differ run to run.
def timing(key):
    k = key.lower()
    return (k.endswith("ms") or "stats" in k or k in ("plannertimes", "stepsoverbudget", "stepsoverbudgetcpu",
            "msperexpansion", "msperfirstexpansion", "maxmb"))

def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if not timing(k) and k != "problem"}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x

def first_diff(a, b, path=""):
    if type(a) != type(b):
        return path or "."
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{path}.{k} (missing on one side)"
            d = first_diff(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{path} (length {len(a)} vs {len(b)})"
        for i, (u, v) in enumerate(zip(a, b)):
            d = first_diff(u, v, f"{path}[{i}]")
            if d:
                return d
        return None
    return None if a == b else f"{path}: {a!r} vs {b!r}"

def run(binary, problem, extra, steps, out):
    cmd = [binary, "--problem", problem, "--steps", str(steps), "--budget-ms", "1e6", "--budget-expansions", "20",
           "--out", out, "--quiet"] + extra
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"same_decisions: {' '.join(cmd)}: exit {p.returncode}: {p.stderr.strip()}")
    with open(out) as f:
        return json.load(f)

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--steps", type=int, default=150)
    ap.add_argument("--only", default="", help="only the runs whose name contains this")
    a = ap.parse_args()
    for f in (RANDOM, WAREHOUSE, RANDOM24):
        if not os.path.exists(f):
            sys.exit(f"same_decisions: {f}: not found (../shared/benchmarks/lorr)")
    bad = 0
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        runs = [r for r in RUNS if a.only in r[0]]
        cells = cells_file(tmp)
        for name, problem, extra in runs:
            extra = [cells if e == CELLS else e for e in extra]
            x = strip(run(a.before, problem, extra, a.steps, os.path.join(tmp, "a.json")))
            y = strip(run(a.after, problem, extra, a.steps, os.path.join(tmp, "b.json")))
            # Builds before issue 20's LifelongRun wrote --executor logs without the robots'
            # start and executed paths (empty lists): compare the rest, and say so.
            # Nor did they share the distance cache: its counters were all 0.
            fixed = [k for k in ("actualPaths", "plannerPaths", "start") if x.get(k) == [] and y.get(k)]
            fixed += [k for k in NEW_KEYS if k in y and k not in x]
            if "distTables" in x and not any(x["distTables"].values()):
                fixed.append("distTables")
            for k in fixed:
                x.pop(k, None), y.pop(k, None)
            same = json.dumps(x, sort_keys=True) == json.dumps(y, sort_keys=True)
            errands = y.get("numErrandFinished")
            print(f"{name:28s} {a.steps} steps, {errands} errands: " +
                  ("identical" if same else "DIFFERENT at " + str(first_diff(x, y))) +
                  (f" (before had no {', '.join(fixed)})" if fixed else ""))
            bad += not same
    print(f"same_decisions: {len(runs) - bad}/{len(runs)} identical (timing fields aside)")
    return 1 if bad else 0

if __name__ == "__main__":
    sys.exit(main())
