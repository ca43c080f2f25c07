#!/usr/bin/env python3
"""What RT-LaCAM*'s first k moves cost (docs/rt_lacam_star.md "Session 45", issue 22).

RT-LaCAM* at --cutoff-ms executes the whole run; for each k, its moves 0..k are kept and
full-horizon LaCAM* (iterative refinement, --anytime-ms) plans the rest from configuration k.
Prints the standard SOC of each such whole plan, checked by rtlacam-check: how much of the
executed cost the first k real-time moves already fixed, however well the rest is planned.

  scripts/rt_prefix_cost.py warehouse-10-20-10-2-1 500 4 --ks 0 10 20 45 80 [--secs 5] [--cutoff-ms 1]
Stdlib only.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("map", help="MovingAI map name (e.g. warehouse-10-20-10-2-1)")
    ap.add_argument("agents", type=int)
    ap.add_argument("scen", type=int, help="random scen number")
    ap.add_argument("--ks", type=int, nargs="+", default=[0, 10, 20, 45, 80])
    ap.add_argument("--secs", type=float, default=5.0, help="LaCAM*'s time for the rest")
    ap.add_argument("--cutoff-ms", type=float, default=1.0)
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "benchmarks", "movingai"))
    ap.add_argument("--bench", default=os.path.join(ROOT, "build", "apps", "rtlacam-bench"))
    ap.add_argument("--check", default=os.path.join(ROOT, "build", "apps", "rtlacam-check"))
    a = ap.parse_args()
    mp = os.path.join(a.data, a.map + ".map")
    sc = os.path.join(a.data, f"{a.map}-random-{a.scen}.scen")
    for p in (mp, sc, a.bench, a.check):
        if not os.path.exists(p):
            sys.exit(f"rt_prefix_cost: {p} not found")
    tmp = tempfile.mkdtemp(prefix="rt_prefix_")

    def bench(args, out):
        r = subprocess.run([a.bench, "--map", mp, "-N", str(a.agents), "--json", "--progress-s", "0", "--out", out] + args,
                           capture_output=True, text=True)
        if r.returncode not in (0, 4):
            sys.exit(f"rt_prefix_cost: rtlacam-bench failed: {r.stderr.strip()}")
        return json.loads(r.stdout)

    def split(path):  # header lines (up to solution=), then the plan's configurations
        head, plan = [], []
        for line in open(path):
            if re.match(r"^\d+:", line):
                plan.append(line.split(":", 1)[1].strip())
            elif not plan:
                head.append(line)
        return head, plan

    rt_plan = os.path.join(tmp, "rt.txt")
    rt = bench(["--scen", sc, "--solver", "rtlacam", "--cutoff-ms", str(a.cutoff_ms)], rt_plan)
    head, executed = split(rt_plan)
    rows = [l.split() for l in open(sc).read().splitlines()[1:a.agents + 1]]
    print(f"{a.map} N={a.agents} scen {a.scen}: RT-LaCAM* at {a.cutoff_ms} ms executed standard SOC {rt['soc']} "
          f"(makespan {rt['makespan']}); the rest from move k by LaCAM* in {a.secs} s:")
    for k in a.ks:
        if k >= len(executed):
            continue
        cells = re.findall(r"\((\d+),(\d+)\)", executed[k])
        kscen = os.path.join(tmp, "k.scen")
        with open(kscen, "w") as f:  # starts = configuration k (x = column, y = row)
            f.write("version 1\n")
            for (x, y), r in zip(cells, rows):
                f.write("\t".join(r[:4] + [x, y] + r[6:9]) + "\n")
        rest_plan = os.path.join(tmp, "rest.txt")
        subprocess.run([a.bench, "--map", mp, "--scen", kscen, "-N", str(a.agents), "--json", "--progress-s", "0",
                        "--out", rest_plan, "--solver", "lacam", "--refine", "--anytime-ms", str(int(a.secs * 1000))],
                       capture_output=True, text=True)
        _, rest = split(rest_plan)
        whole = os.path.join(tmp, "whole.txt")
        with open(whole, "w") as f:
            f.writelines(l for l in head if not l.startswith("solution"))
            f.write("solution=\n")
            for t, line in enumerate(executed[:k + 1] + rest[1:]):
                f.write(f"{t}:{line}\n")
        c = subprocess.run([a.check, "--map", mp, "--scen", sc, "-N", str(a.agents), "--plan", whole],
                           capture_output=True, text=True)
        j = json.loads(c.stdout)
        print(f"  k = {k:4d}: valid {j['valid']}, standard SOC {j['soc']}")


if __name__ == "__main__":
    main()
