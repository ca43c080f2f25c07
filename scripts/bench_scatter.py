#!/usr/bin/env python3
"""SUO (scatter) on / off for RT-LaCAM* at one cutoff: the four 1 ms cells that missed 1.15 x
lacam3 (or --cells all: the 13 cells of sweep_refine_1ms.sh), scens 1..S, variants alternated
per instance in the same time window. Prints per-variant median executed SOC/LB per cell and
the ratio to the first variant and to lacam3 10 s.

  scripts/bench_scatter.py [--cutoff-ms 1] [--scens 5] [--variant NAME=FLAGS ...] [--budget-expansions K]

--budget-expansions K > 0 replaces the wall cutoff (deterministic runs).

FLAGS starting with "bin=PATH" run that binary instead of --bin (old vs new code in one window):
  --variant old="bin=/tmp/rtlacam-bench-old --scatter" --variant new=--scatter
"""
import argparse, json, statistics, subprocess, sys

LACAM3 = {("random-32-32-20", 100): 1.09, ("random-32-32-20", 200): 1.31, ("random-32-32-20", 300): 1.70,
          ("random-32-32-20", 400): 2.57, ("room-32-32-4", 50): 1.13, ("room-32-32-4", 100): 1.30,
          ("room-32-32-4", 150): 1.59, ("warehouse-10-20-10-2-1", 100): 1.01, ("warehouse-10-20-10-2-1", 200): 1.03,
          ("warehouse-10-20-10-2-1", 300): 1.13, ("warehouse-10-20-10-2-1", 400): 1.41}
FOUR = [("random-32-32-20", 200), ("random-32-32-20", 300), ("warehouse-10-20-10-2-1", 200), ("warehouse-10-20-10-2-1", 300)]
ALL = [("random-32-32-20", n) for n in (100, 200, 300, 400)] + [("room-32-32-4", n) for n in (50, 100, 150)] + \
      [("warehouse-10-20-10-2-1", n) for n in (100, 200, 300, 400, 500, 600)]

ap = argparse.ArgumentParser()
ap.add_argument("--cutoff-ms", default="1")
ap.add_argument("--budget-expansions", default="0")
ap.add_argument("--scens", type=int, default=5)
ap.add_argument("--cells", default="four", choices=["four", "all"])
ap.add_argument("--variant", action="append", help="NAME=FLAGS (default: off=--no-scatter, on=--scatter)")
ap.add_argument("--bin", default="./build/apps/rtlacam-bench")
ap.add_argument("--movingai", default="../shared/benchmarks/movingai")
a = ap.parse_args()
variants = [v.split("=", 1) for v in (a.variant or ["off=--no-scatter", "on=--scatter"])]
cells = FOUR if a.cells == "four" else ALL
res = {}
for m, n in cells:
    for k in range(1, a.scens + 1):
        for name, flags in variants:
            fl = flags.split()
            binary = fl.pop(0)[4:] if fl and fl[0].startswith("bin=") else a.bin
            cmd = [binary, "--map", f"{a.movingai}/{m}.map", "--scen", f"{a.movingai}/{m}-random-{k}.scen", "-N", str(n),
                   "--solver", "rtlacam", "--refine", "--seed", "0", "--timeout-s", "20", "--json", "--progress-s", "0"] + fl
            # an expansions budget alone (deterministic), else the wall cutoff
            cmd += ["--budget-expansions", a.budget_expansions] if a.budget_expansions != "0" else ["--cutoff-ms", a.cutoff_ms]
            out = subprocess.run(cmd, capture_output=True, text=True).stdout.strip().splitlines()
            j = json.loads(out[-1])
            r = j["soc"] / j["soc_lb"] if j["solved"] else float("inf")
            res.setdefault((m, n, name), []).append((r, j["solved"], j["valid"]))
            print(m, n, k, name, j["solved"], j["valid"], round(r, 3), flush=True)
print("\n| map | N | " + " | ".join(f"{v[0]}" for v in variants) + " | lacam3 | ratios to lacam3 |")
print("|---|---:|" + "---:|" * len(variants) + "---:|---|")
bad = 0
for m, n in cells:
    meds = [statistics.median(r for r, _, _ in res[(m, n, v[0])]) for v in variants]
    bad += sum(1 for v in variants for _, s, ok in res[(m, n, v[0])] if not (s and ok))
    l3 = LACAM3.get((m, n))
    rat = " ".join(f"{x / l3:.3f}" for x in meds) if l3 else "-"
    print(f"| {m} | {n} | " + " | ".join(f"{x:.3f} ({x / meds[0]:.3f})" for x in meds) + f" | {l3 or '-'} | {rat} |")
print(f"unsolved or invalid runs: {bad}")
