#!/usr/bin/env python3
"""Pool-mode task reassignment vs keeping every assignment, from two lifelong_sweep.py
result files of the same problems, solvers and budgets (measured in the same bench run).

  compare_reassign.py out/lifelong/2024-greedy/results.json out/lifelong/2024-greedy-keep/results.json
"""
import json
import sys


def key(j):
    return (j["instance"], j["assigner"], j["solver"], j["budgetMs"])


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        new = {key(j): j for j in json.load(f)}
    with open(sys.argv[2]) as f:
        base = {key(j): j for j in json.load(f)}
    print("| instance | agents | assigner | solver | budget ms | keep tasks/step | reassign tasks/step | ratio | reassignments |")
    print("|---|---:|---|---|---:|---:|---:|---:|---:|")
    ratios = []
    for k in sorted(new, key=lambda k: (k[0], k[1], k[2], k[3])):
        if k not in base:
            continue
        n, b = new[k], base[k]
        r = n["throughput"] / b["throughput"] if b["throughput"] > 0 else float("inf")
        ratios.append(r)
        print(f"| {k[0]} | {n['teamSize']} | {k[1]} | {k[2]} | {k[3]:g} | {b['throughput']:.3f} | {n['throughput']:.3f} | "
              f"{r:.2f} | {n.get('numReassignments', '-')} |")
    if ratios:
        ratios.sort()
        print(f"\nratio reassign/keep over {len(ratios)} runs: min {ratios[0]:.2f}, median {ratios[len(ratios) // 2]:.2f}, "
              f"max {ratios[-1]:.2f}")


if __name__ == "__main__":
    main()
