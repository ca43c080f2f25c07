#!/usr/bin/env python3
"""LNS neighbourhoods of RT-LaCAM* (lns_refiner.hpp) against each other, one run each.

Median executed SOC/LB of rtlacam-bench --solver rtlacam --refine --cutoff-ms C
--lns-neighbourhood H over scens 1..S of the cells where 1 ms missed 1.15x of lacam3
(random-32-32-20 N=200/300, warehouse-10-20-10-2-1 N=200/300), and the ratio of each
neighbourhood to `random` (the previous default) measured in the same run.

  scripts/bench_lns_neighbourhood.py --cutoff-ms 1 --scens 5
"""
import argparse, json, os, statistics, subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
M = os.path.join(ROOT, "../shared/benchmarks/movingai")
CELLS = [("random-32-32-20", 200), ("random-32-32-20", 300),
         ("warehouse-10-20-10-2-1", 200), ("warehouse-10-20-10-2-1", 300)]
ap = argparse.ArgumentParser()
ap.add_argument("--cutoff-ms", default="1")
ap.add_argument("--scens", type=int, default=5)
ap.add_argument("--nbh", default="random adaptive blocking intersection")
ap.add_argument("--bench", default=os.path.join(ROOT, "build/apps/rtlacam-bench"))
a = ap.parse_args()
nbhs = a.nbh.split()
print("| cell | " + " | ".join(nbhs) + " |")
print("|---|" + "---:|" * len(nbhs))
for m, n in CELLS:
    med = {}
    for h in nbhs:
        r = []
        for k in range(1, a.scens + 1):
            out = subprocess.run([a.bench, "--map", f"{M}/{m}.map", "--scen", f"{M}/{m}-random-{k}.scen", "-N", str(n),
                                  "--solver", "rtlacam", "--refine", "--cutoff-ms", a.cutoff_ms, "--seed", "0",
                                  "--timeout-s", "20", "--json", "--progress-s", "0", "--lns-neighbourhood", h],
                                 capture_output=True, text=True).stdout
            j = json.loads(out.strip().splitlines()[-1])
            assert j.get("valid", True), (m, n, k, h)
            r.append(j["soc"] / j["soc_lb"] if j.get("solved", True) else float("inf"))
        med[h] = statistics.median(r)
    print(f"| {m} N={n} | " + " | ".join(f"{med[h]:.3f} ({med[h] / med[nbhs[0]]:.3f})" for h in nbhs) + " |", flush=True)
