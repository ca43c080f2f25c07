#!/usr/bin/env python3
"""Like-for-like comparison of RT-LaCAM* with peer planners (lacam3, lacam), issue 22.

Every planner runs on the same instances (map, scen, N) on this machine, one after the
other, and every plan -- ours and theirs -- is checked by one checker, rtlacam-check (the
project's Validator), which also computes the costs: the standard sum of costs (each agent
charged up to its last arrival, as lacam3 reports it) and the sum of loss. Ratios are ours /
peer's on the standard SOC, per cell, then their geometric mean and the count within 1.15x.

Ours: rtlacam-bench --solver rtlacam at --cutoff-ms per iteration (RT-LaCAM*; --ours-args
adds options, e.g. "--no-refine" for the paper's RT-LaCAM). --variant NAME=ARGS (repeatable)
runs several settings of ours on every instance in the same run, each with its own columns and
ratios (e.g. before / after: --variant loss="--objective loss" --variant soc="--objective soc"). Peers: `-m MAP -i SCEN -N N
-t SECONDS -o FILE` (the CLI of Kei18's lacam and lacam3), each at --peer-time-s. Peers'
binaries are given by path; they are not part of this repository.

  scripts/peer_bench.py --lacam3 /work/peers/lacam3/build/main \\
      --cells warehouse-10-20-10-2-1:100,400 random-32-32-20:100,200 --scens 1 2 --peer-time-s 10
Stdlib only.
"""
import argparse
import concurrent.futures
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# MOVINGAI_DIR (optional) is searched first: a machine without ../shared (device_issue22.sh).
DATA = ([os.environ["MOVINGAI_DIR"]] if os.environ.get("MOVINGAI_DIR") else []) + \
    [os.path.join(ROOT, "data", "movingai"), os.path.join(ROOT, "..", "shared", "benchmarks", "movingai")]


def fail(msg):
    sys.exit(f"peer_bench: {msg}")


def find(name):
    for d in DATA:
        p = os.path.join(d, name)
        if os.path.exists(p):
            return p
    fail(f"{name} not found in {' or '.join(DATA)}")


def check(args, m, scen, n, plan):
    out = subprocess.run([args.check, "--map", m, "--scen", scen, "-N", str(n), "--plan", plan],
                         capture_output=True, text=True)
    if out.returncode not in (0, 3):
        fail(f"rtlacam-check on {plan}: {out.stderr.strip()}")
    return json.loads(out.stdout)


def run_ours(args, m, scen, n, plan, extra):
    own = args.ours_args.split() + extra.split()
    # A variant may set its own budget (e.g. --variant c001="--cutoff-ms 0.01"): then it replaces --cutoff-ms;
    # and its own solver (e.g. --variant star="--solver lacam --refine --anytime-ms 10000", LaCAM* planned
    # before moving, against a peer's time): then it replaces --solver rtlacam.
    cutoff = [] if "--cutoff-ms" in own else ["--cutoff-ms", str(args.cutoff_ms)]
    solver = [] if "--solver" in own else ["--solver", "rtlacam"]
    cmd = [args.bench, "--map", m, "--scen", scen, "-N", str(n), *solver, *cutoff,
           "--timeout-s", str(args.ours_timeout_s), "--json", "--progress-s", "0", "--out", plan, *own]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode not in (0, 4):
        fail(f"{' '.join(cmd)} failed: {out.stderr.strip()}")
    j = json.loads(out.stdout)
    return j["solved"], j.get("p99_iteration_cpu_ms", 0.0), j.get("max_iteration_cpu_ms", 0.0)


def run_peer(binary, args, m, scen, n, plan):
    cmd = [binary, "-m", m, "-i", scen, "-N", str(n), "-t", str(args.peer_time_s), "-o", plan,
           *args.peer_args.split()]
    # A peer run that dies (lacam3's refiner threads did, now and then, on a loaded box: no
    # output, or no solution, where a rerun solves) gets one more try; both are reported.
    for attempt in (1, 2):
        if os.path.exists(plan):
            os.remove(plan)
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=args.peer_time_s * 3 + 60)
        solved = out.returncode == 0 and os.path.exists(plan)
        if solved:
            with open(plan) as f:
                solved = any(line.strip() == "solved=1" for line in f)
        if solved:
            return True
        print(f"# {os.path.basename(binary)} on {os.path.basename(scen)} N={n}, try {attempt}: exit {out.returncode}, "
              f"no solution", file=sys.stderr)
    return False


def instance_row(args, peers, variants, tmp, i, inst):
    """One instance (map, N, scen): ours (every variant) and every peer, checked; the row and
    its ratios. Runs in a worker thread: its plan files are its own (prefix i)."""
    m_name, n, k = inst
    m = find(m_name + ".map")
    scen = find(f"{m_name}-random-{k}.scen")
    row = f"{m_name:24} {n:>4} {k:>4}"
    ours, ratios = {}, []
    for name, extra in variants:
        plan = os.path.join(tmp, f"{i}-ours.txt")
        solved, p99, _ = run_ours(args, m, scen, n, plan, extra)
        o = check(args, m, scen, n, plan) if solved else None
        if o and not o["valid"]:
            fail(f"our plan ({name}) on {m_name} N={n} scen {k} is invalid: {o['error']}")
        ours[name] = o
        row += f" {o['soc']:>9} {o['sum_of_loss']:>8} {p99:>7.3f}" if o else f" {'unsolved':>9} {'-':>8} {'-':>7}"
    for pname, path in peers:
        pplan = os.path.join(tmp, f"{i}-{pname}.txt")
        theirs = check(args, m, scen, n, pplan) if run_peer(path, args, m, scen, n, pplan) else None
        if theirs and not theirs["valid"]:
            row += f" {'invalid':>11} {'-':>8}" + f" {'-':>7}" * len(variants)
            print(f"# {pname} on {m_name} N={n} scen {k}: {theirs['error']}", file=sys.stderr)
            continue
        if not theirs:
            row += f" {'unsolved':>11} {'-':>8}" + f" {'-':>7}" * len(variants)
            continue
        row += f" {theirs['soc']:>11} {theirs['sum_of_loss']:>8}"
        for name, _ in variants:
            r = ours[name]["soc"] / theirs["soc"] if ours[name] else float("inf")
            ratios.append(((pname, name), r))
            row += f" {r:>7.3f}"
    return row, ratios


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lacam3", help="path to lacam3's binary (build/main)")
    ap.add_argument("--lacam", help="path to lacam's binary (build/main)")
    ap.add_argument("--cells", nargs="+", required=True, metavar="MAP:N,N",
                    help="maps (MovingAI names without .map) and agent counts")
    ap.add_argument("--scens", nargs="+", type=int, default=[1], help="scen numbers (-random-K.scen)")
    ap.add_argument("--cutoff-ms", type=float, default=1.0, help="our per-iteration budget")
    ap.add_argument("--ours-timeout-s", type=float, default=60, help="our cumulative planning time limit")
    ap.add_argument("--ours-args", default="", help="more rtlacam-bench options (e.g. --no-refine)")
    ap.add_argument("--variant", action="append", default=[], metavar="NAME=ARGS",
                    help="a setting of ours (rtlacam-bench options), run on every instance; repeatable")
    ap.add_argument("--peer-time-s", type=float, default=10, help="peers' time limit (-t)")
    ap.add_argument("--peer-args", default="", help="more peer options (e.g. --no-star for lacam3)")
    ap.add_argument("--jobs", type=int, default=1,
                    help="instances run at once (each planner keeps its own threads: lacam3 runs refiner "
                         "threads, so leave cores for them; the default 1 runs one after the other)")
    ap.add_argument("--bench", default=os.path.join(ROOT, "build", "apps", "rtlacam-bench"))
    ap.add_argument("--check", default=os.path.join(ROOT, "build", "apps", "rtlacam-check"))
    args = ap.parse_args()
    if args.jobs < 1:
        fail(f"--jobs must be at least 1, not {args.jobs}")
    peers = [(name, path) for name, path in (("lacam3", args.lacam3), ("lacam", args.lacam)) if path]
    if not peers:
        fail("give at least one peer binary (--lacam3 PATH or --lacam PATH)")
    for name, path in peers + [("rtlacam-bench", args.bench), ("rtlacam-check", args.check)]:
        if not os.access(path, os.X_OK):
            fail(f"{name} binary {path} is not executable")
    variants = []
    for v in args.variant:
        name, eq, extra = v.partition("=")
        if not eq or not name:
            fail(f"bad variant '{v}' (NAME=ARGS)")
        variants.append((name, extra))
    if not variants:
        variants = [("ours", "")]
    cells = []
    for c in args.cells:
        m, _, ns = c.partition(":")
        try:
            cells += [(m, int(n)) for n in ns.split(",")]
        except ValueError:
            fail(f"bad cell '{c}' (MAP:N,N,...)")

    print(f"# ours: rtlacam-bench --solver rtlacam --cutoff-ms {args.cutoff_ms} {args.ours_args}".rstrip() +
          ("  (a variant's own --solver or --cutoff-ms replaces it)" if args.variant else ""))
    for name, extra in variants:
        if extra or len(variants) > 1:
            print(f"# variant {name}: {extra}")
    print(f"# peers at {args.peer_time_s} s {args.peer_args}".rstrip() + "; every plan checked by rtlacam-check;"
          " SOC = standard (last arrival), loss = sum of loss")
    head = f"{'map':24} {'N':>4} {'scen':>4}"
    for name, _ in variants:
        head += f" {name + ' SOC':>9} {'loss':>8} {'p99cpu':>7}"
    for pname, _ in peers:
        head += f" {pname + ' SOC':>11} {'loss':>8}"
        for name, _ in variants:
            head += f" {'r.' + name:>7}"
    print(head)
    ratios = {(pname, name): [] for pname, _ in peers for name, _ in variants}
    instances = [(m_name, n, k) for m_name, n in cells for k in args.scens]
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        # Rows print in instance order as they finish; each instance has its own plan files.
        rows = [pool.submit(instance_row, args, peers, variants, tmp, i, inst) for i, inst in enumerate(instances)]
        for f in rows:
            row, rs = f.result()
            for key, r in rs:
                ratios[key].append(r)
            print(row, flush=True)
    for (pname, name), rs in ratios.items():
        who = "ours" if len(variants) == 1 and name == "ours" else f"ours ({name})"
        finite = [r for r in rs if math.isfinite(r)]
        if not rs:
            print(f"# {who} / {pname}: no cell solved by both")
            continue
        gm = math.exp(sum(math.log(r) for r in finite) / len(finite)) if finite else float("inf")
        print(f"# {who} / {pname} on standard SOC: {len(rs)} cells, geometric mean {gm:.3f}, "
              f"range {min(rs):.3f}-{max(rs):.3f}, within 1.15x on {sum(r <= 1.15 for r in rs)}/{len(rs)}, "
              f"within 1.5x on {sum(r <= 1.5 for r in rs)}/{len(rs)}")


if __name__ == "__main__":
    main()
