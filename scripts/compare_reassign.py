#!/usr/bin/env python3
"""Pool-mode task reassignment vs keeping every assignment, from two lifelong_sweep.py
result files of the same problems, solvers and budgets (measured in the same bench run).

  compare_reassign.py REASSIGN.json KEEP.json [--png out.png]

e.g. out/lifelong/2024-greedy-reassign/results.json out/lifelong/2024-greedy/results.json
(scripts/lifelong_bench.sh). The PNG shows throughput vs agents per solver at the largest
budget, with and without reassignment.
"""
import argparse
import json
import sys


def key(j):
    return (j["instance"], j["assigner"], j["solver"], j["budgetMs"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("new", help="results.json of the --reassign sweep")
    ap.add_argument("base", help="results.json of the same sweep without it")
    ap.add_argument("--png", help="write the plot here")
    args = ap.parse_args()
    with open(args.new) as f:
        new = {key(j): j for j in json.load(f)}
    with open(args.base) as f:
        base = {key(j): j for j in json.load(f)}
    print("| instance | agents | assigner | solver | budget ms | keep tasks/step | reassign tasks/step | ratio | reassignments |")
    print("|---|---:|---|---|---:|---:|---:|---:|---:|")
    ratios = []
    for k in sorted(new, key=lambda k: (k[0], k[1], k[2], k[3])):
        if k not in base:
            continue
        n, b = new[k], base[k]
        r = n["taskThroughput"] / b["taskThroughput"] if b["taskThroughput"] > 0 else float("inf")
        ratios.append(r)
        print(f"| {k[0]} | {n['teamSize']} | {k[1]} | {k[2]} | {k[3]:g} | {b['taskThroughput']:.3f} | {n['taskThroughput']:.3f} | "
              f"{r:.2f} | {n.get('numReassignments', '-')} |")
    if ratios:
        ratios.sort()
        print(f"\nratio reassign/keep over {len(ratios)} runs: min {ratios[0]:.2f}, median {ratios[len(ratios) // 2]:.2f}, "
              f"max {ratios[-1]:.2f}")

    if args.png:
        plot(new, base, args.png)


def plot(new, base, png):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no PNG (use ${PYTHON:-/usr/bin/python3})", file=sys.stderr)
        return
    budget = max(k[3] for k in new)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    colors = {"pibt": "tab:green", "naive": "tab:brown", "rtlacam": "tab:olive"}
    assigner = next(iter(new))[1]
    for solver in ["pibt", "naive", "rtlacam"]:
        for data, style, label in [(new, "-", "reassign"), (base, ":", "keep")]:
            pts = sorted((j["teamSize"], j["taskThroughput"]) for k, j in data.items() if k[2] == solver and k[3] == budget)
            if pts:
                ax.plot(*zip(*pts), style, marker="o", color=colors[solver], label=f"{solver} {label}")
    ax.set_xlabel("agents")
    ax.set_ylabel("tasks finished per step")
    ax.set_title(f"LoRR 2024 random-32-32-20, pool/{assigner}, {budget:g} ms: reassignment vs keep")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wrote {png}", file=sys.stderr)


if __name__ == "__main__":
    main()
