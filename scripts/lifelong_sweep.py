#!/usr/bin/env python3
"""Throughput vs agents per solver on LoRR problems: runs rtlacam-lifelong on every
(problem, solver, budget), keeps each JSON log, writes a Markdown table (with the
published LoRR best beside ours) and a PNG.

    scripts/lifelong_sweep.py --bin build/apps/rtlacam-lifelong \
        --problems ../shared/benchmarks/lorr/2023/random.domain/MR23-I-0{4,3,5,7,8}.json \
        --solvers pibt naive rtlacam --budget-ms 1 10 100 --out-dir out/lifelong/2023

Plotting needs matplotlib: run with ${PYTHON:-/usr/bin/python3} (Debian's Python).
"""
import argparse
import json
import os
import subprocess
import sys

# Best published results (benchmarks README: LoRR rules, rotation action model, 1 s/step on
# 32 vCPUs): context, not like-for-like. 2023 = errands/step, 2024 = tasks/step.
LORR_BEST = {
    "MR23-I-04": 3.48, "MR23-I-03": 6.08, "MR23-I-05": 7.43, "MR23-I-07": 5.91, "MR23-I-08": 3.03,
    "MR23-I-10": 38.9, "RANDOM-01": 1.16, "RANDOM-03": 2.96, "WAREHOUSE": 31.0,
}


def run(args, problem, solver, budget, extra):
    name = os.path.splitext(os.path.basename(problem))[0]
    tag = f"{name}{'-' + extra['tag'] if extra.get('tag') else ''}_{solver}_{budget:g}ms"
    log = os.path.join(args.out_dir, tag + ".json")
    if not (args.reuse and os.path.exists(log)):
        cmd = [args.bin, "--problem", problem, "--solver", solver, "--budget-ms", str(budget), "--seed", str(args.seed),
               "--assigner", args.assigner, "--out", log, "--progress-s", "30"]
        cmd += extra.get("cli", [])
        print(" ".join(cmd), file=sys.stderr, flush=True)
        r = subprocess.run(cmd, stdout=subprocess.DEVNULL)
        if r.returncode != 0:
            print(f"  failed with exit code {r.returncode}", file=sys.stderr)
            return None
    with open(log) as f:
        j = json.load(f)
    j.pop("events", None)
    j["instance"] = name
    return j


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="build/apps/rtlacam-lifelong")
    ap.add_argument("--problems", nargs="+", required=True)
    ap.add_argument("--solvers", nargs="+", default=["pibt", "naive", "rtlacam"])
    ap.add_argument("--budget-ms", nargs="+", type=float, default=[100.0])
    ap.add_argument("--assigner", default="greedy")
    ap.add_argument("--agents", type=int, default=0, help="first N agents only (e.g. warehouse)")
    ap.add_argument("--steps", type=int, default=0, help="override the instance's step count")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("--reuse", action="store_true", help="keep existing logs instead of re-running")
    ap.add_argument("--reassign", action="store_true", help="pool: nearer free agents may take unopened tasks")
    args = ap.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    extra = {"cli": [], "tag": ""}
    if args.agents:
        extra["cli"] += ["--agents", str(args.agents)]
        extra["tag"] += f"n{args.agents}"
    if args.steps:
        extra["cli"] += ["--steps", str(args.steps)]
        extra["tag"] += f"t{args.steps}"
    if args.reassign:
        extra["cli"] += ["--reassign"]
        extra["tag"] += "steal"

    rows = []
    for p in args.problems:
        for b in args.budget_ms:
            for s in args.solvers:
                j = run(args, p, s, b, extra)
                if j:
                    rows.append(j)
    with open(os.path.join(args.out_dir, "results.json"), "w") as f:
        json.dump(rows, f, indent=1)

    lines = ["| instance | agents | steps | mode | solver | budget ms | finished | per step | LoRR best/step | p99 ms | max ms | errors |",
             "|---|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for j in rows:
        best = LORR_BEST.get(j["instance"]) if not args.agents else None
        mode = j["mode"] + ("/" + j["assigner"] + ("/reassign" if j.get("reassign") else "") if j["mode"] == "pool" else "")
        lines.append(f"| {j['instance']} | {j['teamSize']} | {j['makespan']} | {mode} | {j['solver']} | {j['budgetMs']:g} | "
                     f"{j['numTaskFinished']} | {j['taskThroughput']:.2f} | {best if best else '-'} | "
                     f"{j['plannerTimeStats']['p99']:.2f} | {j['plannerTimeStats']['max']:.1f} | {j['numPlannerErrors']} |")
    table = "\n".join(lines) + "\n"
    with open(os.path.join(args.out_dir, "table.md"), "w") as f:
        f.write(table)
    print(table)

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no PNG (use ${PYTHON:-/usr/bin/python3})", file=sys.stderr)
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    styles = {"pibt": "o-", "naive": "s--", "rtlacam": "^-"}
    for s in args.solvers:
        for b in args.budget_ms:
            pts = sorted((j["teamSize"], j["taskThroughput"]) for j in rows if j["solver"] == s and j["budgetMs"] == b)
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], styles.get(s, "x-"), label=f"{s} {b:g} ms",
                        alpha=0.5 + 0.5 * (b == max(args.budget_ms)))
    best = sorted((j["teamSize"], LORR_BEST[j["instance"]]) for j in rows
                  if j["instance"] in LORR_BEST and j["solver"] == args.solvers[0] and j["budgetMs"] == args.budget_ms[0]
                  and not args.agents)
    if best:
        ax.plot([p[0] for p in best], [p[1] for p in best], "k:", marker="*", label="LoRR best (rotation, 1 s/step)")
    ax.set_xlabel("agents")
    ax.set_ylabel("finished per step (" + ("tasks" if rows and rows[0]["mode"] == "pool" else "errands") + ")")
    ax.set_title(args.title or "Lifelong throughput vs agents")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    png = os.path.join(args.out_dir, "throughput.png")
    fig.savefig(png, dpi=120)
    print("wrote", png, file=sys.stderr)


if __name__ == "__main__":
    main()
