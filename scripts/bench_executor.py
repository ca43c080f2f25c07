#!/usr/bin/env python3
"""Lockstep vs the ADG executor under delays (issue 10's bench table).

For each delay probability p (Bernoulli, per AGV per tick, stops of 1-5 ticks):
  A. SUMO, large warehouse (200 AGVs, one-shot): makespan in ticks (1 tick = 1 s) for
     lockstep (scheme S, all wait for a stopped mover), adg (Hoenig's rule) and adg-follow
     (moving-block following), both with physics (0.5 / 1.0 m/s^2) and continuous motion.
  B. MAPF graph, rtlacam-lifelong on LoRR RANDOM-01 (100 agents): errands per step, lockstep,
     adg (Hoenig's rule) and adg-follow (moving-block following).
  C. SUMO, small warehouse lifelong (16 AGVs, 1000 ticks): errands per tick, lockstep, adg
     and adg-follow.
Each run also reports its collisions / moveTo jumps (must be 0). Writes docs/executor_bench.md
(markdown) and prints it.

  scripts/bench_executor.py [--build build] [--max-ticks 3000] [--parts ABC] [--out docs/executor_bench.md]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PS = [0, 0.001, 0.01, 0.05]


def yaml_variant(src, executor, p, accel=None, decel=None, window=16, max_ticks=None, slow=False):
    """The config `src` with the executor, the delays and the physics replaced."""
    s = open(os.path.join(ROOT, "config", src)).read()
    s = re.sub(r"\ndelays:\n(  .*\n)*", "\n", s)
    s = re.sub(r"  executor: [\w-]+.*\n", "", s)
    s = re.sub(r"  window: \d+\n", "", s)
    s = s.replace("run:\n", f"run:\n  executor: {executor}\n  window: {window}\n")
    if accel is not None:
        s = re.sub(r"accel: [0-9.]+, decel: [0-9.]+", f"accel: {accel}, decel: {decel}", s)
    if max_ticks:
        s = re.sub(r"max_ticks: \d+", f"max_ticks: {max_ticks}", s)
    d = f"delays:\n  kind: bernoulli\n  p: {p}\n  duration_s: [1, 5]\n  seed: 0\n"
    if slow:
        d += "  slow: [{agent: 0, factor: 0.7}]\n"
    s = s.replace("output:\n", d + "output:\n")
    f = tempfile.NamedTemporaryFile("w", suffix=".yaml", dir=os.path.join(ROOT, "config"), delete=False)
    f.write(s)
    f.close()
    return f.name


def sumo_run(build, cfg, out):
    t0 = time.time()
    subprocess.run([os.path.join(build, "apps", "rtlacam-sumo"), cfg, "--out", out], capture_output=True, text=True)
    os.unlink(cfg)
    m = json.load(open(os.path.join(out, "metrics.json")))
    m["_wall"] = time.time() - t0
    return m


def part_a(build, max_ticks, tmp):
    rows = []
    variants = [("lockstep", "lockstep", None, None), ("adg", "adg", 0.5, 1.0), ("adg-follow", "adg-follow", 0.5, 1.0)]
    for p in PS:
        row = [p]
        for name, ex, a, d in variants:
            cfg = yaml_variant("large_warehouse_agv.yaml", ex, p, a, d, max_ticks=max_ticks)
            m = sumo_run(build, cfg, os.path.join(tmp, f"A_{ex}_{a}_{p}"))
            bad = int(m["collisions"]) + int(m["teleports_or_jumps"]) + (1 if m["error"] else 0)
            cell = f"{m['ticks']}" if m["solved"] else f">{m['ticks']} (unsolved)"
            row.append(f"{cell}{' ERR' if bad else ''}")
            print(f"A p={p} {name}: ticks {m['ticks']} solved {m['solved']} error '{m['error']}' "
                  f"dep_waits {m['executor']['dependency_waits']} wall {m['_wall']:.1f}s", file=sys.stderr)
        rows.append(row)
    head = "| p | lockstep | adg, physics 0.5/1.0 m/s^2 | adg-follow, physics 0.5/1.0 m/s^2 |\n|---:|---:|---:|---:|\n"
    return head + "".join(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} |\n" for r in rows)


def part_b(build, steps):
    rows = []
    prob = os.path.join(ROOT, "tests/data/tasks/lorr/2024/random.domain/RANDOM-01.json")
    for p in PS:
        row = [p]
        for ex in ["lockstep", "adg", "adg-follow"]:
            r = subprocess.run([os.path.join(build, "apps", "rtlacam-lifelong"), "--problem", prob, "--budget-ms", "1",
                                "--budget-expansions", "50", "--steps", str(steps), "--executor", ex, "--window", "4",
                                "--delay-kind", "bernoulli", "--delay-p", str(p), "--delay-min", "1", "--delay-max", "5",
                                "--quiet"], capture_output=True, text=True)
            j = json.loads(r.stdout)
            row.append(f"{j['numErrandFinished'] / steps:.3f} (K={j['executor']['maxTicksWithoutErrand']})")
            print(f"B p={p} {ex}: errands {j['numErrandFinished']} rc {r.returncode}", file=sys.stderr)
        rows.append(row)
    head = "| p | lockstep | adg (W=4) | adg-follow (W=4) |\n|---:|---:|---:|---:|\n"
    return head + "".join(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} |\n" for r in rows)


def part_c(build, tmp):
    rows = []
    for p in PS:
        row = [p]
        for name, ex, a, d in [("lockstep", "lockstep", None, None), ("adg, physics", "adg", 0.5, 1.0),
                               ("adg-follow, physics", "adg-follow", 0.5, 1.0)]:
            cfg = yaml_variant("small_warehouse_lifelong_agv.yaml", ex, p, a, d, window=4)
            m = sumo_run(build, cfg, os.path.join(tmp, f"C_{ex}_{p}"))
            bad = int(m["collisions"]) + int(m["teleports_or_jumps"]) + (1 if m["error"] else 0)
            life = m["lifelong"]
            row.append(f"{life['errandThroughput']:.3f}{' ERR' if bad else ''}")
            print(f"C p={p} {name}: errands {life['numErrandFinished']} error '{m['error']}' "
                  f"wall {m['_wall']:.1f}s", file=sys.stderr)
        rows.append(row)
    head = "| p | lockstep | adg, physics 0.5/1.0 m/s^2 | adg-follow, physics 0.5/1.0 m/s^2 |\n|---:|---:|---:|---:|\n"
    return head + "".join(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} |\n" for r in rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--max-ticks", type=int, default=3000)
    ap.add_argument("--steps", type=int, default=1000, help="part B: steps per lifelong run")
    ap.add_argument("--parts", default="ABC")
    ap.add_argument("--ps", default=",".join(map(str, PS)), help="delay probabilities, comma-separated")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "executor_bench.md"))
    a = ap.parse_args()
    PS[:] = [float(x) if "." in x else int(x) for x in a.ps.split(",")]
    tmp = tempfile.mkdtemp(prefix="bench_executor_")
    md = ["# Lockstep vs ADG executor under delays\n",
          f"`scripts/bench_executor.py --parts {a.parts} --max-ticks {a.max_ticks} --steps {a.steps}`, "
          f"{time.strftime('%Y-%m-%d')}. Delays: Bernoulli stops starting with probability p per AGV per "
          "tick, 1-5 ticks (s) long. ERR would mark a run with a collision, a moveTo jump or an error.\n"]
    if "A" in a.parts:
        md += ["\n## A. SUMO, large warehouse, 200 AGVs, one-shot: makespan (ticks of 1 s)\n\n",
               part_a(a.build, a.max_ticks, tmp)]
    if "B" in a.parts:
        md += ["\n## B. MAPF graph, rtlacam-lifelong, LoRR RANDOM-01 (100 agents): errands per step "
               "(K = longest run of steps without an errand)\n\n", part_b(a.build, a.steps)]
    if "C" in a.parts:
        md += ["\n## C. SUMO, small warehouse lifelong, 16 AGVs, 1000 ticks: errands per tick\n\n", part_c(a.build, tmp)]
    text = "".join(md)
    with open(a.out, "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
