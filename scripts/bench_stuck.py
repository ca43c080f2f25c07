#!/usr/bin/env python3
"""A stuck AGV: the others route on (run.replan_on_stuck) vs they wait (the ADG alone).

  A. config/small_warehouse_stuck.yaml (4 AGVs, agv0 stuck in the cross aisle the others'
     plans use), stuck for 10 / 30 / 60 / 120 s from t = 0: when the others finish, the
     makespan, replans; ratio replan / wait.
  B. config/small_warehouse_agv.yaml (16 random AGVs, its random stops removed, 50 expansions
     per SUMO step instead of 1 ms: deterministic), agent k stuck 60 s from t = 5 s,
     k = 0..K-1: makespan and flowtime (sum of arrival times) with and without the replan.
  C. the same 16 AGVs with frequent long stops (p = 0.01 per AGV per tick, 3-25 s) and one
     AGV stuck 40 s, seeds 0..S-1: makespan without the replan, with it (stuck_after_s 5 and 15).
Every run must end with no error (Safety after every SUMO step), 0 collisions, 0 jumps.
Prints markdown (and writes it with --out).

  scripts/bench_stuck.py [--build build] [--agents 16] [--seeds 12] [--out docs/stuck_replan_bench.md]
                         [--svg docs/stuck_replan.svg]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def variant(src, replan, stuck, expansions=None):
    """The config `src` with run.replan_on_stuck and delays.stuck replaced."""
    s = open(os.path.join(ROOT, "config", src)).read()
    s = re.sub(r"  replan_on_stuck: \w+\n", "", s)
    s = s.replace("run:\n", f"run:\n  replan_on_stuck: {'true' if replan else 'false'}\n")
    s = re.sub(r"\ndelays:\n(  .*\n)*", "\n", s)
    s = s.replace("output:\n", f"delays:\n  stuck: [{stuck}]\noutput:\n")
    # Deterministic: a budget in expansions, not wall-clock (the two runs must differ only
    # by the replan).
    if expansions:
        s = re.sub(r"budget_ms: [0-9.]+", f"budget_ms: 0\n  expansions: {expansions}", s)
    f = tempfile.NamedTemporaryFile("w", suffix=".yaml", dir=os.path.join(ROOT, "config"), delete=False)
    f.write(s)
    f.close()
    return f.name


def run(build, cfg, out):
    t0 = time.time()
    subprocess.run([os.path.join(build, "apps", "rtlacam-sumo"), cfg, "--out", out], capture_output=True, text=True)
    os.unlink(cfg)
    m = json.load(open(os.path.join(out, "metrics.json")))
    m["_wall"] = time.time() - t0
    bad = int(m["collisions"]) + int(m["teleports_or_jumps"]) + (1 if m["error"] else 0) + (0 if m["solved"] else 1)
    if bad:
        print(f"BAD RUN {out}: error '{m['error']}' solved {m['solved']}", file=sys.stderr)
    m["_bad"] = bad
    return m


def svg_plot(curves, frees, path):
    """AGVs on their goals over time (step curves) for the 60 s case; `curves`: {label: goal_s}."""
    W, H, L, B = 640, 300, 50, 40
    tmax = max(max(g) for g in curves.values()) * 1.05
    n = max(len(g) for g in curves.values())
    x = lambda t: L + (W - L - 20) * t / tmax
    y = lambda k: H - B - (H - B - 20) * k / n
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<line x1="{L}" y1="{y(0)}" x2="{W - 20}" y2="{y(0)}" stroke="black"/>',
           f'<line x1="{L}" y1="{y(0)}" x2="{L}" y2="20" stroke="black"/>',
           f'<text x="{W / 2}" y="{H - 8}" text-anchor="middle">simulated time (s)</text>',
           f'<text x="14" y="{H / 2}" transform="rotate(-90 14 {H / 2})" text-anchor="middle">AGVs on their goals</text>']
    for t in range(0, int(tmax) + 1, 20):
        out.append(f'<text x="{x(t)}" y="{y(0) + 15}" text-anchor="middle">{t}</text>')
    for k in range(n + 1):
        out.append(f'<text x="{L - 8}" y="{y(k) + 4}" text-anchor="end">{k}</text>')
    out.append(f'<line x1="{x(frees)}" y1="{y(0)}" x2="{x(frees)}" y2="20" stroke="gray" stroke-dasharray="4 3"/>')
    out.append(f'<text x="{x(frees) + 4}" y="30" fill="gray">agv0 frees</text>')
    for (label, goal_s), color, dy in zip(curves.items(), ["#c33", "#36c"], [0, 16]):
        pts, k = [(0, 0)], 0
        for t in sorted(goal_s):
            pts += [(t, k), (t, k + 1)]
            k += 1
        pts.append((tmax, k))
        out.append(f'<polyline fill="none" stroke="{color}" stroke-width="2" points="' +
                   " ".join(f"{x(t):.1f},{y(c):.1f}" for t, c in pts) + '"/>')
        out.append(f'<text x="{L + 10}" y="{36 + dy}" fill="{color}">{label}</text>')
    out.append("</svg>")
    open(path, "w").write("\n".join(out) + "\n")


def part_a(build, tmp, svg=None):
    head = ("| stuck for | others done, wait | others done, replan | makespan wait | makespan replan | ratio | replans |\n"
            "|---:|---:|---:|---:|---:|---:|---:|\n")
    rows = ""
    for dur in [10, 30, 60, 120]:
        ms = {}
        for replan in [False, True]:
            cfg = variant("small_warehouse_stuck.yaml", replan, f"{{agent: 0, at_s: 0, for_s: {dur}}}")
            ms[replan] = run(build, cfg, os.path.join(tmp, f"A_{dur}_{replan}"))
        if svg and dur == 60:
            svg_plot({"ADG alone: the others wait": ms[False]["executor"]["goal_s"],
                      "replan_on_stuck: the others route on": ms[True]["executor"]["goal_s"]}, dur, svg)
        others = {k: max(m["executor"]["goal_s"][1:]) for k, m in ms.items()}
        mk = {k: m["makespan"] for k, m in ms.items()}
        flag = " ERR" if ms[False]["_bad"] + ms[True]["_bad"] else ""
        rows += (f"| {dur} s | {others[False]:.1f} s | {others[True]:.1f} s | {mk[False]} | {mk[True]} | "
                 f"{mk[True] / mk[False]:.2f} | {ms[True]['executor']['replans']}{flag} |\n")
        print(f"A {dur}: {rows.splitlines()[-1]}", file=sys.stderr)
    return head + rows


def part_b(build, agents, tmp):
    head = ("| stuck AGV | makespan wait | makespan replan | ratio | flowtime wait | flowtime replan | ratio | "
            "replans |\n|---:|---:|---:|---:|---:|---:|---:|---:|\n")
    m0 = run(build, variant("small_warehouse_agv.yaml", True, "", expansions=50), os.path.join(tmp, "B_none"))
    rows = (f"| none stuck | {m0['makespan']} | {m0['makespan']} | 1.00 | {sum(m0['executor']['goal_s']):.0f} | "
            f"{sum(m0['executor']['goal_s']):.0f} | 1.00 | {m0['executor']['replans']} |\n")
    sums = [0, 0, 0, 0]
    for k in range(agents):
        ms = {}
        for replan in [False, True]:
            cfg = variant("small_warehouse_agv.yaml", replan, f"{{agent: {k}, at_s: 5, for_s: 60}}", expansions=50)
            ms[replan] = run(build, cfg, os.path.join(tmp, f"B_{k}_{replan}"))
        mk = {r: m["makespan"] for r, m in ms.items()}
        ft = {r: sum(m["executor"]["goal_s"]) for r, m in ms.items()}
        sums = [sums[0] + mk[False], sums[1] + mk[True], sums[2] + ft[False], sums[3] + ft[True]]
        flag = " ERR" if ms[False]["_bad"] + ms[True]["_bad"] else ""
        e = ms[True]["executor"]
        rows += (f"| agv{k} | {mk[False]} | {mk[True]} | {mk[True] / mk[False]:.2f} | {ft[False]:.0f} | {ft[True]:.0f} | "
                 f"{ft[True] / ft[False]:.2f} | {e['replans']}{flag} |\n")
        print(f"B {k}: {rows.splitlines()[-1]}", file=sys.stderr)
    rows += (f"| all stuck cases | {sums[0]} | {sums[1]} | {sums[1] / sums[0]:.2f} | {sums[2]:.0f} | {sums[3]:.0f} | "
             f"{sums[3] / sums[2]:.2f} | |\n")
    return head + rows


def part_c(build, seeds, tmp):
    """Frequent long stops: p = 0.01 per AGV per tick, 3-25 s, plus one AGV stuck 40 s."""
    head = ("| seed | makespan wait | replan, stuck_after_s 5 | ratio | replan, stuck_after_s 15 | ratio | replans (5 s / 15 s) |\n"
            "|---:|---:|---:|---:|---:|---:|---:|\n")
    rows, sums = "", [0, 0, 0]
    for seed in range(seeds):
        ms = []
        for replan, after in [(False, 5), (True, 5), (True, 15)]:
            cfg = variant("small_warehouse_agv.yaml", replan, f"{{agent: {seed % 16}, at_s: {seed % 7 + 1}, for_s: 40}}",
                          expansions=50)
            t = open(cfg).read().replace("delays:\n", f"delays:\n  kind: bernoulli\n  p: 0.01\n  duration_s: [3, 25]\n"
                                                     f"  seed: {seed}\n")
            t = t.replace("run:\n", f"run:\n  stuck_after_s: {after}\n")
            open(cfg, "w").write(t)
            ms.append(run(build, cfg, os.path.join(tmp, f"C_{seed}_{replan}_{after}")))
        mk = [m["makespan"] for m in ms]
        sums = [a + b for a, b in zip(sums, mk)]
        flag = " ERR" if sum(m["_bad"] for m in ms) else ""
        rows += (f"| {seed} | {mk[0]} | {mk[1]} | {mk[1] / mk[0]:.2f} | {mk[2]} | {mk[2] / mk[0]:.2f} | "
                 f"{ms[1]['executor']['replans']} / {ms[2]['executor']['replans']}{flag} |\n")
        print(f"C {seed}: {rows.splitlines()[-1]}", file=sys.stderr)
    rows += f"| all | {sums[0]} | {sums[1]} | {sums[1] / sums[0]:.2f} | {sums[2]} | {sums[2] / sums[0]:.2f} | |\n"
    return head + rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--agents", type=int, default=16)
    ap.add_argument("--seeds", type=int, default=12)
    ap.add_argument("--out")
    ap.add_argument("--svg", help="AGVs on their goals over time, stuck 60 s (docs/stuck_replan.svg)")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="bench_stuck_")
    t0 = time.time()
    md = "## A. small_warehouse_stuck.yaml: agv0 stuck in the cross aisle from t = 0\n\n" + part_a(a.build, tmp, a.svg)
    md += ("\n## B. small_warehouse_agv.yaml (16 AGVs, random stops removed, 50 expansions per step): one AGV stuck 60 s from t = 5 s\n\n" +
           part_b(a.build, a.agents, tmp))
    md += ("\n## C. small_warehouse_agv.yaml (16 AGVs, 50 expansions per step), frequent long stops (p = 0.01 per AGV "
           "per tick, 3-25 s) and one AGV stuck 40 s\n\n" + part_c(a.build, a.seeds, tmp))
    md += f"\n(wall {time.time() - t0:.0f} s; makespan in ticks of 1 s; flowtime = sum of the AGVs' arrival times, s)\n"
    print(md)
    if a.out:
        open(a.out, "w").write(md)


if __name__ == "__main__":
    main()
