#!/usr/bin/env python3
"""Completions over time of one rtlacam-lifelong run (its --out log): cumulative errands
and tasks finished per step, with the per-step rate (moving average) on a second axis.

    ${PYTHON:-/usr/bin/python3} scripts/plot_lifelong.py out/run.json -o out/run.png [more logs...]

Several logs are drawn on one figure (e.g. the three solvers on one instance).
"""
import argparse
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("logs", nargs="+")
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--window", type=int, default=25, help="moving-average window (steps)")
    args = ap.parse_args()

    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for path in args.logs:
        with open(path) as f:
            j = json.load(f)
        if "events" not in j:  # the summary rtlacam-lifelong prints on stdout leaves them out
            sys.exit(f"plot_lifelong.py: {path} has no 'events': pass the log of --out (or rtlacam-sumo's lifelong.json)")
        T = j["makespan"]
        per_step = [0] * (T + 1)
        for e in j["events"]:
            if j.get("version") == "2023 LoRR":  # per agent: [task, t, "assigned" | "finished"]
                for task, t, what in e:
                    per_step[t] += what == "finished"
            else:  # [t, agent, task, errands done]
                per_step[e[0]] += 1
        cum, c = [], 0
        for t in range(T + 1):
            c += per_step[t]
            cum.append(c)
        w = max(1, args.window)
        rate = [(cum[t] - cum[max(0, t - w)]) / min(w, t) if t else 0 for t in range(T + 1)]
        label = f"{j['solver']} {j['budgetMs']:g} ms ({j['numErrandFinished']} errands, {j['numTaskFinished']} tasks)"
        ax.plot(range(T + 1), cum, label=label)
        ax2.plot(range(T + 1), rate, label=j["solver"])
    name = j["problem"].split("/")[-1]
    ax.set_title(f"{name}: {j['teamSize']} agents, {j['mode']}" + (f"/{j['assigner']}" if j["mode"] == "pool" else ""))
    ax.set_ylabel("errands finished (cumulative)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    ax2.set_ylabel(f"errands/step ({args.window}-step avg)")
    ax2.set_xlabel("step")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
