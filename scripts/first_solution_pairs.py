#!/usr/bin/env python3
"""LaCAM's first solution under variants of one binary (issue 22): deterministic, so one run
per instance is enough and the box's load does not matter. Per instance the standard SOC of
every variant, run one after the other; per variant the ratio to the first variant (geometric
mean, on how many instances lower / higher). It is what RT-LaCAM* at 0.01 ms executes on
most cells (docs/rt_lacam_star.md) and where the 1 ms runs start from.

A variant is NAME=OPTIONS (rtlacam-bench options, one argument, split on spaces):

  scripts/first_solution_pairs.py --variant off="--no-free-first" --variant on="--free-first"
  scripts/first_solution_pairs.py --mode rt001 --variant off="--no-free-first" --variant on=""

--mode lacam (default): full-horizon LaCAM, `--solver lacam --no-refine`; --mode rt001:
RT-LaCAM* at `--cutoff-ms 0.01` (not deterministic in principle: a wall budget, but one
expansion per iteration at that cutoff). Default cells: the issue's 13 (random-32-32-20 N =
100-400, warehouse-10-20-10-2-1 N = 100-600, room-32-32-4 N = 50-150), scens 1-5.
Stdlib only.
"""
import argparse
import json
import math
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CELLS = ["random-32-32-20:100,200,300,400", "warehouse-10-20-10-2-1:100,200,300,400,500,600", "room-32-32-4:50,100,150"]
MODES = {"lacam": ["--solver", "lacam", "--no-refine"], "rt001": ["--solver", "rtlacam", "--cutoff-ms", "0.01"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--variant", action="append", required=True, help="NAME=OPTIONS; the first is the baseline")
    ap.add_argument("--bench", default=os.path.join(ROOT, "build", "apps", "rtlacam-bench"))
    ap.add_argument("--mode", choices=sorted(MODES), default="lacam")
    ap.add_argument("--cells", nargs="+", default=CELLS, metavar="MAP:N,N")
    ap.add_argument("--scens", nargs="+", type=int, default=[1, 2, 3, 4, 5])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--data", default=os.environ.get("DATA", os.path.join(ROOT, "..", "shared", "benchmarks", "movingai")))
    a = ap.parse_args()
    variants = []
    for v in a.variant:
        name, sep, opts = v.partition("=")
        if not sep or not name:
            sys.exit(f"first_solution_pairs: --variant {v!r}: expected NAME=OPTIONS")
        variants.append((name, opts.split()))
    if not os.access(a.bench, os.X_OK):
        sys.exit(f"first_solution_pairs: {a.bench}: not an executable (build rtlacam-bench or pass --bench)")
    print(f"# {a.bench} {' '.join(MODES[a.mode])} --seed {a.seed}; standard SOC; ratios to {variants[0][0]}")
    print("map N scen " + " ".join(name for name, _ in variants))
    ratios = [[] for _ in variants]
    for cell in a.cells:
        m, _, ns = cell.partition(":")
        for n in (int(x) for x in ns.split(",")):
            for s in a.scens:
                row = []
                for _, opts in variants:
                    cmd = [a.bench, "--map", os.path.join(a.data, f"{m}.map"), "--scen",
                           os.path.join(a.data, f"{m}-random-{s}.scen"), "-N", str(n), *MODES[a.mode],
                           "--seed", str(a.seed), *opts, "--json"]
                    out = subprocess.run(cmd, capture_output=True, text=True)
                    if out.returncode not in (0, 4):
                        sys.exit(f"first_solution_pairs: {' '.join(cmd)}: {out.stderr.strip()}")
                    j = json.loads(out.stdout)
                    row.append(j["soc"] if j["solved"] else None)
                print(m, n, s, *("-" if x is None else x for x in row),
                      *(f"{x / row[0]:.3f}" for x in row[1:] if x and row[0]), flush=True)
                for k, x in enumerate(row):
                    if x and row[0]:
                        ratios[k].append(x / row[0])
    for k, (name, _) in enumerate(variants[1:], 1):
        r = ratios[k]
        if not r:
            continue
        gm = math.exp(sum(map(math.log, r)) / len(r))
        print(f"# {name} / {variants[0][0]}: gm {gm:.4f} over {len(r)}, lower {sum(x < 1 for x in r)}, "
              f"higher {sum(x > 1 for x in r)}, range {min(r):.3f}-{max(r):.3f}")


if __name__ == "__main__":
    main()
