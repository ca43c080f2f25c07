#!/usr/bin/env python3
"""Paired budget runs of RT-LaCAM* (issue 22): variants alternated per instance, one after
the other, so that a loaded box's drift hits them alike. Per run: the planning thread's CPU
p99 / max iteration (what preemption does not inflate) and the standard SOC; per variant:
the median p99, how many p99 exceed 1.1x / 1.5x the cutoff, the median and largest max, how
many max exceed 1.5x, and the SOC over the first variant's on the same instance and
repetition (geometric mean, and on how many it is lower).

A variant is NAME=BINARY [OPTIONS...] (one argument, split on spaces):

  scripts/budget_pairs.py --cells warehouse-20-40-10-2-2:1000 --scens 1 2 3 --reps 2 \\
      --variant "old=/work/s35/rtlacam-bench.main" --variant "new=build/apps/rtlacam-bench"
  scripts/budget_pairs.py ... --variant "new=build/apps/rtlacam-bench" \\
      --variant "no-pause=build/apps/rtlacam-bench --no-dive-pause"
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--variant", action="append", required=True, help="NAME=BINARY [OPTIONS]; the first is the baseline")
    ap.add_argument("--cells", nargs="+", default=["warehouse-20-40-10-2-2:1000"], help="MAP:N")
    ap.add_argument("--scens", nargs="+", type=int, default=[1, 2, 3])
    ap.add_argument("--reps", type=int, default=2)
    ap.add_argument("--cutoff-ms", type=float, default=1.0)
    ap.add_argument("--data", default=os.environ.get("DATA", os.path.join(ROOT, "..", "shared", "benchmarks", "movingai")))
    a = ap.parse_args()
    variants = []
    for v in a.variant:
        name, _, cmd = v.partition("=")
        if not cmd:
            sys.exit(f"budget_pairs.py: variant '{v}' is not NAME=BINARY [OPTIONS]")
        variants.append((name, cmd.split()))
    for name, cmd in variants:
        if not os.access(cmd[0], os.X_OK):
            sys.exit(f"budget_pairs.py: variant {name}: '{cmd[0]}' is not executable")
    rows = {name: [] for name, _ in variants}
    t0 = time.time()
    for rep in range(a.reps):
        for cell in a.cells:
            m, n = cell.split(":")
            for s in a.scens:
                mp, sc = f"{a.data}/{m}.map", f"{a.data}/{m}-random-{s}.scen"
                if not os.path.exists(sc):
                    sys.exit(f"budget_pairs.py: no {sc} (set --data)")
                for name, cmd in variants:
                    out = subprocess.run(["nice"] + cmd[:1] + ["--map", mp, "--scen", sc, "-N", n, "--solver", "rtlacam",
                                          "--json", "--progress-s", "0", "--timeout-s", "120"]
                                         + ([] if "--cutoff-ms" in cmd else ["--cutoff-ms", str(a.cutoff_ms)])
                                         + cmd[1:], capture_output=True, text=True).stdout
                    j = json.loads(out[out.index("{"):out.rindex("}") + 1])
                    r = dict(key=(rep, cell, s), ok=bool(j["solved"] and j["valid"]), soc=j["soc"],
                             p99=j.get("p99_iteration_cpu_ms", 0), mx=j.get("max_iteration_cpu_ms", 0))
                    rows[name].append(r)
                    print(f"rep {rep} {cell} scen {s} {name:10s} ok {int(r['ok'])} SOC {r['soc']} SOC/LB {j['norm_soc']:.3f} "
                          f"cpu p99 {r['p99']:.3f} max {r['mx']:.3f} iterations {j['iterations']}", flush=True)
    c = a.cutoff_ms
    base = {r["key"]: r for r in rows[variants[0][0]]}
    print(f"# {len(rows[variants[0][0]])} runs per variant, cutoff {c} ms, {time.time() - t0:.0f} s in all")
    for name, _ in variants:
        rs = rows[name]
        p99 = [r["p99"] for r in rs]
        mx = [r["mx"] for r in rs]
        ratios = [r["soc"] / base[r["key"]]["soc"] for r in rs if r["ok"] and base[r["key"]]["ok"]]
        gm = math.exp(sum(math.log(x) for x in ratios) / len(ratios)) if ratios else float("nan")
        print(f"{name:10s} ok {sum(r['ok'] for r in rs)}/{len(rs)} p99 median {statistics.median(p99):.3f} "
              f"(> 1.1x {sum(p > 1.1 * c for p in p99)}, > 1.5x {sum(p > 1.5 * c for p in p99)}) "
              f"max median {statistics.median(mx):.3f} largest {max(mx):.3f} (> 1.5x {sum(m > 1.5 * c for m in mx)}) "
              f"SOC/{variants[0][0]} gm {gm:.3f} lower {sum(x < 1 for x in ratios)}/{len(ratios)}")


if __name__ == "__main__":
    main()
