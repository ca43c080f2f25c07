#!/usr/bin/env python3
"""Planner benchmark (issue 2 targets), apart from the tests.

For each map, agent count and scen 1..K it runs, in the same process session:
  - full-horizon LaCAM with swap (the baseline), and without swap (vanilla),
  - RT-LaCAM at cutoffs 0.01 .. 100 ms: the paper's planner (rtlacam-bench --no-refine --no-resumable
    --no-reserve: no LaCAM* refinement, expansions until the cutoff as the paper's loop),
and prints one table row per instance: LaCAM's first-solution time, RT-LaCAM's total
planning time as a ratio of it, whether RT-LaCAM built the identical tree (same
expansions and explored size), and the p99 / max iteration time at cutoff 1 ms.
A summary (medians, worst ratio) follows. Stdlib only.

  scripts/bench_planner.py [--bin build/apps/rtlacam-bench] [--scens 5] [--timeout-s 10] [--quick]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SETS = [
    ("random-32-32-20", [100, 200, 300, 400]),
    ("room-32-32-4", [50, 100, 150]),
    ("warehouse-10-20-10-2-1", [100, 200, 400, 600]),
]
CUTOFFS = [0.01, 0.1, 1, 10, 100]
PAPER = ["--no-refine", "--no-reserve", "--no-resumable"]  # the paper's RT-LaCAM (the CLI's rtlacam is RT-LaCAM*)


def run(binary, m, k, n, solver, timeout, extra=()):
    d = os.path.join(ROOT, "data", "movingai")
    cmd = [binary, "--map", f"{d}/{m}.map", "--scen", f"{d}/{m}-random-{k}.scen", "-N", str(n),
           "--solver", solver, "--timeout-s", str(timeout), "--json", *extra]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode not in (0, 4):  # 4: unsolved (a timeout), still a result
        sys.exit(f"bench_planner: {' '.join(cmd)} failed: {out.stderr.strip()}")
    return json.loads(out.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "apps", "rtlacam-bench"))
    ap.add_argument("--scens", type=int, default=5)
    ap.add_argument("--timeout-s", type=float, default=10)
    ap.add_argument("--quick", action="store_true", help="one scen, cutoffs 0.1 and 1 only")
    a = ap.parse_args()
    cutoffs = [0.1, 1] if a.quick else CUTOFFS
    scens = 1 if a.quick else a.scens

    print(f"RT-LaCAM = the paper's planner: rtlacam-bench --solver rtlacam {' '.join(PAPER)}")
    head = ["map", "N", "k", "lacam ms", "vanilla ms"] + [f"rt@{c}" for c in cutoffs] + ["same tree", "p99@1ms", "max@1ms"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    lacam_ms, vanilla_ms, ratios, p99s, solved, same = [], [], {c: [] for c in cutoffs}, [], 0, 0
    total = 0
    for m, ns in SETS:
        for n in ns:
            for k in range(1, scens + 1):
                total += 1
                base = run(a.bin, m, k, n, "lacam", a.timeout_s)
                van = run(a.bin, m, k, n, "lacam", a.timeout_s, ["--no-swap"])
                row = [m, str(n), str(k), f"{base['total_planning_ms']:.1f}" + ("" if base["solved"] else " FAIL"),
                       f"{van['total_planning_ms']:.0f}" + ("" if van["solved"] else " FAIL")]
                if base["solved"]:
                    solved += 1
                    lacam_ms.append(base["total_planning_ms"])
                if van["solved"]:
                    vanilla_ms.append(van["total_planning_ms"])
                tree_ok = True
                p99 = mx = float("nan")
                for c in cutoffs:
                    rt = run(a.bin, m, k, n, "rtlacam", a.timeout_s, ["--cutoff-ms", str(c), *PAPER])
                    r = rt["total_planning_ms"] / base["total_planning_ms"]
                    ratios[c].append(r)
                    row.append(f"{r:.2f}" + ("" if rt["solved"] == base["solved"] else " (solved differs)"))
                    tree_ok &= rt["expansions"] == base["expansions"] and rt["explored"] == base["explored"]
                    if c == 1:
                        p99, mx = rt["p99_iteration_ms"], rt["max_iteration_ms"]
                        p99s.append(p99)
                same += tree_ok
                row += ["yes" if tree_ok else "NO", f"{p99:.3f}", f"{mx:.3f}"]
                print("| " + " | ".join(row) + " |", flush=True)

    print()
    print(f"LaCAM (swap) solved {solved}/{total}; median first-solution time {statistics.median(lacam_ms):.1f} ms, "
          f"max {max(lacam_ms):.1f} ms")
    if vanilla_ms:
        print(f"vanilla LaCAM solved {len(vanilla_ms)}/{total}; median {statistics.median(vanilla_ms):.1f} ms")
    print(f"identical tree (expansions and explored equal at every cutoff): {same}/{total}")
    for c in cutoffs:
        print(f"RT-LaCAM / LaCAM total planning time at cutoff {c} ms: median {statistics.median(ratios[c]):.3f}, "
              f"max {max(ratios[c]):.3f}")
    print(f"p99 iteration time at cutoff 1 ms: median {statistics.median(p99s):.3f} ms, max {max(p99s):.3f} ms")


if __name__ == "__main__":
    main()
