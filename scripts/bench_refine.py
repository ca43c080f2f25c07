#!/usr/bin/env python3
"""RT-LaCAM* (refinement) benchmark: executed SOC/LB of four planners per instance.

  rtlacam*   rtlacam-bench --solver rtlacam --refine      (RT-LaCAM*, this project's default)
  rtlacam    rtlacam-bench --solver rtlacam --no-refine   (the paper's RT-LaCAM)
  lacam      rtlacam-bench --solver lacam                 (full horizon, first solution)
  lacam*     rtlacam-bench --solver lacam --refine --anytime-ms T
             refine-after-solve: full-horizon LaCAM* that plans for the same total time T
             as rtlacam* used on that instance and cutoff, then executes

at per-iteration cutoffs (default 0.01 0.1 1 10 ms) on random-32-32-20 N=100..400,
room-32-32-4 N=50..150, warehouse-10-20-10-2-1 N=100..600, scens 1..5 (55 instances).
One JSON line per run is appended to OUT/results.jsonl (runs already there are skipped:
an interrupted sweep resumes). --report writes OUT/refine.md (medians, ratio to lacam3's
10 s anytime numbers) and OUT/refine.png (Fig. 2 third row style).

  scripts/bench_refine.py --out docs/refine --cutoffs "0.01 0.1 1"
  scripts/bench_refine.py --out docs/refine --report-only
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GRID = {
    "random-32-32-20": [100, 200, 300, 400],
    "room-32-32-4": [50, 100, 150],
    "warehouse-10-20-10-2-1": [100, 200, 300, 400, 500, 600],
}
# lacam3, 10 s anytime, median SOC/LB (issue 9).
LACAM3 = {
    ("random-32-32-20", 100): 1.09, ("random-32-32-20", 200): 1.31, ("random-32-32-20", 300): 1.70,
    ("random-32-32-20", 400): 2.57, ("warehouse-10-20-10-2-1", 100): 1.01, ("warehouse-10-20-10-2-1", 200): 1.03,
    ("warehouse-10-20-10-2-1", 300): 1.13, ("warehouse-10-20-10-2-1", 400): 1.41,
    ("room-32-32-4", 50): 1.13, ("room-32-32-4", 100): 1.30, ("room-32-32-4", 150): 1.59,
}
SOLVERS = ["rtlacam*", "rtlacam", "lacam*", "lacam"]


def key(v, m, n, k, c):
    return f"{v}|{m}|{n}|{k}|{c}"


def load(path):
    out = {}
    if os.path.exists(path):
        for line in open(path):
            try:
                j = json.loads(line)
                out[j["run_key"]] = j
            except (ValueError, KeyError):
                pass
    return out


def run(args, variant, m, n, k, c, anytime_ms=0.0):
    d = os.path.join(ROOT, "data/movingai")
    cmd = [args.bench, "--map", f"{d}/{m}.map", "--scen", f"{d}/{m}-random-{k}.scen", "-N", str(n), "--json",
           "--timeout-s", str(args.timeout_s), "--seed", str(args.seed)]
    if variant in ("rtlacam*", "rtlacam"):
        cmd += ["--solver", "rtlacam", "--cutoff-ms", str(c), "--refine" if variant == "rtlacam*" else "--no-refine"]
    elif variant == "lacam*":
        cmd += ["--solver", "lacam", "--refine", "--anytime-ms", str(anytime_ms)]
    else:
        cmd += ["--solver", "lacam", "--no-refine"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    try:
        j = json.loads(p.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        j = {"solved": False, "valid": False, "crash": p.returncode, "stderr": p.stderr[-300:]}
    j.update(run_key=key(variant, m, n, k, c), variant=variant, map_name=m, N=n, scen_k=k, cutoff=c)
    return j


def sweep(args):
    res_path = os.path.join(args.out, "results.jsonl")
    done = load(res_path)
    cutoffs = [float(x) for x in args.cutoffs.split()]
    inst = [(m, n, k) for m, ns in GRID.items() for n in ns for k in range(1, args.scens + 1)]

    def one(job):
        m, n, k = job
        lines = []
        if key("lacam", m, n, k, 0) not in done:
            lines.append(run(args, "lacam", m, n, k, 0))
        for c in cutoffs:
            for v in ("rtlacam", "rtlacam*"):
                if key(v, m, n, k, c) not in done:
                    lines.append(run(args, v, m, n, k, c))
            if key("lacam*", m, n, k, c) not in done:
                star = done.get(key("rtlacam*", m, n, k, c)) or next(
                    (x for x in lines if x["run_key"] == key("rtlacam*", m, n, k, c)), None)
                t = star["total_planning_ms"] if star and star.get("solved") else args.timeout_s * 1000
                lines.append(run(args, "lacam*", m, n, k, c, t))
        with open(res_path, "a") as f:
            for x in lines:
                f.write(json.dumps(x) + "\n")
        bad = [x["run_key"] for x in lines if not x.get("valid", False) and x.get("solved")]
        print(f"{m} N={n} scen {k}: {len(lines)} runs" + (f"  INVALID {bad}" if bad else ""), flush=True)

    with ThreadPoolExecutor(args.jobs) as ex:
        list(ex.map(one, inst))


def report(args):
    rows = load(os.path.join(args.out, "results.jsonl")).values()
    cutoffs = sorted({r["cutoff"] for r in rows if r["variant"] != "lacam"})
    cell = {}
    for r in rows:
        cs = [r["cutoff"]] if r["variant"] != "lacam" else cutoffs
        for c in cs:
            cell.setdefault((r["variant"], r["map_name"], r["N"], c), []).append(r)

    def med(v, m, n, c):
        rs = cell.get((v, m, n, c), [])
        # an unsolved run counts as infinitely bad, as in a success-aware median
        vals = [r["norm_soc"] if r.get("solved") and r.get("valid") else float("inf") for r in rs]
        return (statistics.median(vals) if vals else None), sum(1 for r in rs if r.get("solved")), len(rs)

    out = ["# RT-LaCAM* benchmark (scripts/bench_refine.py)", "",
           "Median executed SOC/LB (unsolved = inf), solved/runs, and the ratio to lacam3's 10 s anytime median.",
           f"Scens 1..{max(r['scen_k'] for r in rows)}; per-run timeout {args.timeout_s} s; seed {args.seed}.", ""]
    invalid = [r["run_key"] for r in rows if r.get("solved") and not r.get("valid")]
    out.append(f"Invalid executed plans: {len(invalid)} {invalid[:5]}")
    for c in cutoffs:
        out += ["", f"## cutoff {c} ms", "",
                "| map | N | lacam3 10 s | " + " | ".join(SOLVERS) + " | rtlacam* / lacam3 |",
                "|---|---:|---:|" + "---:|" * (len(SOLVERS) + 1)]
        for m, ns in GRID.items():
            for n in ns:
                ref = LACAM3.get((m, n))
                cells, star = [], None
                for v in SOLVERS:
                    x, s, t = med(v, m, n, c)
                    if v == "rtlacam*":
                        star = x
                    cells.append("-" if x is None else f"{x:.3f} ({s}/{t})")
                ratio = f"{star / ref:.3f}" if ref and star not in (None, float("inf")) else "-"
                out.append(f"| {m} | {n} | {ref if ref else '-'} | " + " | ".join(cells) + f" | {ratio} |")
    with open(os.path.join(args.out, "refine.md"), "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(out))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(GRID), figsize=(5 * len(GRID), 4))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, (m, ns) in zip(axes, GRID.items()):
        for ci, c in enumerate(cutoffs):
            for v, style in (("rtlacam*", "-"), ("rtlacam", ":")):
                ys = [med(v, m, n, c)[0] for n in ns]
                ax.plot(ns, [y if y not in (None, float("inf")) else float("nan") for y in ys], style, marker="o",
                        color=colors[ci % len(colors)], label=f"{v} {c:g} ms")
        ys = [med("lacam", m, n, cutoffs[0])[0] for n in ns]
        ax.plot(ns, ys, "--", color="gray", marker="s", label="lacam (first)")
        refs = [(n, LACAM3[(m, n)]) for n in ns if (m, n) in LACAM3]
        ax.plot([a for a, _ in refs], [b for _, b in refs], "k*", markersize=10, label="lacam3 10 s")
        ax.set_title(m)
        ax.set_xlabel("agents")
        ax.set_ylabel("executed SOC / LB (median)")
        ax.set_yscale("log")
        ax.grid(alpha=0.3)
    axes[-1].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "refine.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(ROOT, "out/refine"))
    ap.add_argument("--bench", default=os.path.join(ROOT, "build/apps/rtlacam-bench"))
    ap.add_argument("--cutoffs", default="0.01 0.1 1 10")
    ap.add_argument("--scens", type=int, default=5)
    ap.add_argument("--timeout-s", type=float, default=30)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("-j", "--jobs", type=int, default=1)
    ap.add_argument("--report-only", action="store_true")
    ap.add_argument("--no-report", action="store_true")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if not args.report_only:
        sweep(args)
    if not args.no_report:
        report(args)


if __name__ == "__main__":
    sys.exit(main())
