#!/usr/bin/env python3
"""Where a physical executor's time goes against lock-step's (issue 21), from SUMO's fcd and the
executed plan.

Runs one instance (bench_closed_loop.py's config plumbing: --config, --seed, --expansions, p = 0)
under each executor with fcd on, or reads runs already made (--runs DIR ...), and splits every
AGV's time to its last arrival (the last SUMO step it moved) into

  distance   its path length at the vType's top speed (what no executor can beat);
  ramps      what rest-to-rest trapezoids over its motion segments (maximal runs between two
             steps at rest) cost beyond that: one pair of ramps per stop -- physics of the
             stops it made;
  slowdown   motion slower than those trapezoids: braking toward a held cell or a leader's
             back and speeding up again without coming to rest;
  rest       steps at rest before its last arrival (waiting for a dependency, a rest before
             a reversal, a release, the plan);

for the AGV that arrives last (its time is the makespan) and summed over the fleet, plus the
count of stops; then the plan's ADG critical path with each move's least physical time (a lower
bound for any ADG executor on that plan) and, for physical executors, the executed critical path
(moves from rest, chained moves, rests, links; from fcd). Beside it, per plan (plan.txt): steps, moves, the longest path in moves, the
reversals (u -> v -> u) and the planned stops (a wait between two moves: an AGV that keeps the
plan's waits comes to rest there). So one sees whether the plan executed is the same length as
lock-step's, and whether the extra ticks are physics (ramps of stops the plan forces), the
executor (slowdown, rests with the dependency met), or waits. With the run's split_trace.txt (adg
runs with fcd on: every AGV's SUMO steps by the Driver's category, DriveStats::Split) it also sums
the executed critical path by category, with the time each category lost against top speed.

  scripts/closed_loop_decompose.py [--build build] [--config large_warehouse_agv.yaml]
        [--seed 1] [--expansions 50] [--executors lockstep adg-follow[:key=value]]
        [--max-ticks 1500] [--out DIR] [--trace N] [--p 0]
  scripts/closed_loop_decompose.py --runs OUT1 OUT2 ...   (each with config.yaml, fcd.xml, plan.txt, metrics.json)
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_executor import yaml_variant  # noqa: E402
from bench_closed_loop import with_agv_vtype, set_run_keys  # noqa: E402
from plan_stop_bound import rest_to_rest_s, read_plan  # noqa: E402


def make_run(a, ex, out):
    """The config of one row (p = --p, default 0) with fcd on, run once; returns the run's folder."""
    name, _, sets = ex.partition(":")
    cfg = yaml_variant(a.config, name, a.p, window=a.window, max_ticks=a.max_ticks)
    with_agv_vtype(cfg)
    set_run_keys(cfg, sets, a.seed, a.expansions)
    s = open(cfg).read()
    os.unlink(cfg)
    s = re.sub(r"fcd: \w+", "fcd: true", s)
    s = s.replace("../sumo_scenarios", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sumo_scenarios"))
    os.makedirs(out, exist_ok=True)
    open(os.path.join(out, "config.yaml"), "w").write(s)
    t0 = time.time()
    subprocess.run([os.path.join(a.build, "apps", "rtlacam-sumo"), os.path.join(out, "config.yaml"), "--out", out],
                   capture_output=True, text=True)
    print(f"ran {ex}: {time.time() - t0:.1f} s wall", file=sys.stderr)
    return out


def vtype(cfg_text):
    m = re.search(r"vtype: \{([^}]*)\}", cfg_text)
    kv = dict(x.strip().split(": ") for x in m.group(1).split(","))
    st = re.search(r"step_length: ([0-9.]+)", cfg_text)
    return float(kv["accel"]), float(kv["decel"]), float(kv["max_speed"]), float(st.group(1)) if st else 0.125


def read_fcd(path):
    """Per vehicle id, its speeds per SUMO step (fcd order)."""
    speeds = {}
    veh = re.compile(r'<vehicle id="([^"]+)".*? speed="([-0-9.]+)"')
    with open(path) as f:
        for line in f:
            m = veh.search(line)
            if m:
                speeds.setdefault(m.group(1), []).append(float(m.group(2)))
    return speeds


def split_time(v, dt, acc, dec, vmax):
    """One AGV's speeds -> (arrival s, distance s, ramps s, slowdown s, rest s, stops)."""
    moving = [k for k, s in enumerate(v) if s > 1e-9]
    if not moving:
        return 0, 0, 0, 0, 0, 0
    end = moving[-1] + 1  # steps up to the last arrival
    dist = sum(v[:end]) * dt
    rest = sum(1 for s in v[:end] if s <= 1e-9) * dt
    tri = 0.0  # rest-to-rest trapezoids over the motion segments
    stops = 0
    k = 0
    while k < end:
        if v[k] <= 1e-9:
            k += 1
            continue
        j = k
        while j < end and v[j] > 1e-9:
            j += 1
        tri += rest_to_rest_s(sum(v[k:j]) * dt, acc, dec, vmax)
        stops += 1
        k = j
    moving_s = end * dt - rest
    return end * dt, dist / vmax, tri - dist / vmax, moving_s - tri, rest, stops


def plan_shape(path):
    """Plan steps, total moves, the longest path in moves, reversals, planned stops (waits between moves)."""
    steps = read_plan(path)
    n = len(steps[0])
    moves = rev = waits = 0
    longest = 0
    for i in range(n):
        seq = [s[i] for s in steps]
        mv = [t for t in range(1, len(seq)) if seq[t] != seq[t - 1]]  # steps that end a move
        moves += len(mv)
        longest = max(longest, len(mv))
        waits += sum(1 for a, b in zip(mv, mv[1:]) if b > a + 1)  # a wait between two moves
        rev += sum(1 for a, b in zip(mv, mv[1:]) if seq[b] == seq[a - 1])  # back where it came from
    return len(steps) - 1, moves, longest, rev, waits


def plan_adg(steps):
    """The plan's moves in plan order (agent, from, to, step), each agent's move ids, and the ADG
    links (executor/adg.hpp, waits dropped): prev[x], the agent's move before x (type 1), and
    hand[x], the move that left x's target cell last before x, by another agent (type 2)."""
    n, T = len(steps[0]), len(steps)
    moves, per = [], [[] for _ in range(n)]
    for t in range(1, T):
        for i in range(n):
            if steps[t][i] != steps[t - 1][i]:
                per[i].append(len(moves))
                moves.append((i, steps[t - 1][i], steps[t][i], t))
    prev, last_leave, hand = {}, {}, {}
    for i in range(n):
        for a, b in zip(per[i], per[i][1:]):
            prev[b] = a
    k = 0
    for t in range(1, T):
        ids = []
        while k < len(moves) and moves[k][3] == t:
            ids.append(k)
            k += 1
        for x in ids:
            last_leave[moves[x][1]] = x
        for x in ids:
            h = last_leave.get(moves[x][2])
            if h is not None and moves[h][0] != moves[x][0]:
                hand[x] = h
    return moves, per, prev, hand


def critical_path(path, acc, dec, vmax, free_reversals=False, gap=None, absorb=None):
    """The plan's ADG (executor/adg.hpp: type 1 an AGV's moves in order, type 2 the move into v after
    v's previous leave; waits dropped) with each move's least physical time -- 1 m at top speed
    (cell / vmax), from rest (first move, and after a reversal, which needs rest) accelerating,
    to rest (before a reversal, and the last move) braking -- and arrivals in ADG order: a move
    ends no earlier than its hand-over's. The longest path is a lower bound on any ADG executor's
    makespan for this plan with these kinematics (rotation groups, which start together, are
    ignored: an estimate there). Returns (length s, on it: moves from rest, moves to rest, moves,
    hand-over links).
    gap (body length + margin, m): the Driver's and Safety's line model too -- a front reaches v only
    once the hand-over's front is `gap` past v on its way out (run on the leader's line), so a move
    into v ends no earlier than the leader's arrival on v plus its least time for `gap` metres (from
    rest if it must stop on v: before a reversal, or its first move). Still a lower bound for
    adg-follow, which adds only the stops the approach cannot avoid: a follower rolls in exactly
    then (perfect anticipation).
    absorb (s, with gap): an idealised executor that absorbs a wait of up to `absorb` s for free
    (rolls in slower) and stops for a longer one -- it stands and starts from rest once it may go,
    arriving a from-rest move after its release. Not a bound: a model of how far anticipation
    would have to reach (0: every wait is a stop). The 6th value returned counts the stops on
    the path."""
    moves, per, prev, hand = plan_adg(read_plan(path))
    cell = 1.0
    up = math.sqrt(2 * cell / acc)  # from rest, 1 m accelerating all the way (<= vmax at 1 m/s, 0.5 m/s^2)
    up = up if acc * up <= vmax else cell / vmax + vmax / (2 * acc)
    down = cell / vmax + vmax / (2 * dec)  # 1 m ending at rest from vmax
    both = rest_to_rest_s(cell, acc, dec, vmax)
    rest_before, rest_after = set(), set()
    for q in per:
        if not q:
            continue
        rest_before.add(q[0])
        rest_after.add(q[-1])
        for a, b in zip(q, q[1:]):
            if moves[b][2] == moves[a][1] and not free_reversals:
                rest_after.add(a)
                rest_before.add(b)
    done = [0.0] * len(moves)
    why = [None] * len(moves)
    stopped = set()
    for x in range(len(moves)):  # ids are in plan order: dependencies come first
        d = both if (x in rest_before and x in rest_after) else up if x in rest_before else \
            down if x in rest_after else cell / vmax
        c = done[prev[x]] + d if x in prev else d
        why[x] = ("prev", prev.get(x), d)
        h = hand.get(x)
        if h is not None and done[h] > c:
            c = done[h]
            why[x] = ("hand", h, 0)
        if h is not None and gap is not None:
            ramp = math.sqrt(2 * gap / acc)
            ramp = ramp if acc * ramp <= vmax else gap / vmax + vmax / (2 * acc)
            lag = ramp if h in rest_before else gap / vmax
            on_v = done[prev[h]] if h in prev else 0.0  # the leader's front on v
            if on_v + lag > c:
                c = on_v + lag
                why[x] = ("hand", h, 0)
        own = done[prev[x]] + d if x in prev else d
        if absorb is not None and c - own > absorb + 1e-9 and x not in rest_before:
            start = max(c - cell / vmax, done[prev[x]] if x in prev else 0.0)  # released
            c = max(c, start + (both if x in rest_after else up))
            stopped.add(x)
        done[x] = c
    x = max(range(len(moves)), key=lambda y: done[y])
    length = done[x]
    fr = to = mv = links = stops = 0
    while x is not None:
        stops += x in stopped
        kind, y, _ = why[x]
        if kind == "hand":
            links += 1
        else:
            mv += 1
            fr += x in rest_before
            to += x in rest_after
        x = y
    return length, fr, to, mv, links, stops


def _dir(u, v):
    return (v[0] - u[0], v[1] - u[1])


def read_split_trace(path):
    """split_trace.txt (written beside the fcd by adg runs): category names by letter, and per
    vehicle id its SUMO steps' letters."""
    if not os.path.exists(path):
        return None, None
    with open(path) as f:
        head = f.readline()
        names = dict(x.split("=") for x in head.split() if "=" in x)
        rows = dict(line.split() if len(line.split()) == 2 else (line.split()[0], "") for line in f if line.strip())
    return names, rows


def executed_path(path, speeds, dt, acc, dec, vmax, trace=None):
    """The executed run's critical path, back from the last arrival: each move's completion and
    start read from fcd (every move is one cell, 1 m on these nets: the fcd distance equals the
    plan's moves to 1 cm), and at each step back the constraint met last -- the hand-over's
    arrival (a link), the leader's start (the AGV waited for it: the path goes on there), the
    AGV's own previous move. Returns seconds on the path by kind: moves from rest and chained
    (with their least times), rests not spent waiting for a leader's start (before a reversal,
    a release held), and the link count."""
    moves, per, prev, hand = plan_adg(read_plan(path))
    n = len(per)
    end, start, rested = {}, {}, {}
    for i in range(n):
        v = speeds.get(f"agv{i}", [])
        cum, j = 0.0, 0
        last_rest = 0  # end time of the last step at rest
        for kk, x in enumerate(per[i]):
            t0 = end[per[i][kk - 1]] if kk else 0.0
            had_rest = False
            while j < len(v) and cum < kk + 1 - 0.02:
                if v[j] <= 1e-9:
                    last_rest = (j + 1) * dt
                    had_rest = had_rest or last_rest > t0 + 1e-9
                cum += v[j] * dt
                j += 1
            end[x] = j * dt
            rested[x] = had_rest or kk == 0
            start[x] = max(t0, last_rest) if rested[x] else t0
    up = math.sqrt(2 / acc) if math.sqrt(2 / acc) * acc <= vmax else 1 / vmax + vmax / (2 * acc)
    out = dict(from_rest=0.0, from_rest_least=0.0, chained=0.0, chained_least=0.0, rest=0.0,
               links=0, n_from_rest=0, n_chained=0, stood=[], events=[], kinds={}, cats={}, lost={})
    names, letters = trace or (None, None)

    def on_path(agent, t0, t1):
        # the Driver's category of each SUMO step of agent's that the path spends in [t0, t1)
        if not letters:
            return
        row, v = letters.get(f"agv{agent}", ""), speeds.get(f"agv{agent}", [])
        for j in range(int(round(t0 / dt)), int(round(t1 / dt))):
            c = names.get(row[j], "?") if j < len(row) else "after trace"
            out["cats"][c] = out["cats"].get(c, 0.0) + dt
            # time lost against top speed in this step (a step at rest loses dt)
            out["lost"][c] = out["lost"].get(c, 0.0) + dt * (1 - min(vmax, v[j] if j < len(v) else 0.0) / vmax)
    x = max(end, key=lambda y: end[y])
    node = ("end", x)
    tol = dt + 1e-9
    visited = set()
    while node:
        # A rotation within one plan step (three or more AGVs each entering the cell the next
        # leaves) makes the hand-over links a cycle of equal arrival times: cut the path there
        # (on the huge warehouse the walk went round one for ever, until 20 GB).
        if node in visited:
            out["events"].append(f"{end[node[1]]:8.2f}   cycle of hand-overs (a rotation within one plan step): path cut")
            out["cycles"] = out.get("cycles", 0) + 1
            break
        visited.add(node)
        kind, x = node
        h = hand.get(x)
        if kind == "end":
            if h is not None and end[h] >= end[x] - tol and end[h] <= end[x] + 1e-9:
                out["links"] += 1
                out["events"].append(f"{end[x]:8.2f} link: agv{moves[x][0]}'s move ends with agv{moves[h][0]}'s arrival")
                node = ("end", h)
                continue
            a_, u_, v_, t_ = moves[x]
            if rested[x]:
                # how long the AGV stood before this start (since its previous move ended)
                out["stood"].append(start[x] - (end[prev[x]] if x in prev else 0.0))
                out["events"].append(f"{start[x]:8.2f} agv{a_} {u_}->{v_} (step {t_}) from rest, {end[x] - start[x]:.2f} s,"
                                     f" after standing {out['stood'][-1]:.2f} s")
                out["from_rest"] += end[x] - start[x]
                on_path(a_, start[x], end[x])
                out["from_rest_least"] += up
                # what it waited for: its leader's start (as the "start" node below), the follower
                # entering on the leader's line out of the cell (a train start) or from another
                # side (a junction passage: it cannot roll in behind the leader's projected body),
                # or no leader (its own rest: a reversal, a first move)
                t0 = end[prev[x]] if x in prev else 0.0
                if h is not None and abs(start[h] - start[x]) <= tol and start[h] > t0 + 1e-9:
                    kind_ = "train start" if _dir(u_, v_) == _dir(moves[h][1], moves[h][2]) else "other side"
                else:
                    kind_ = "no leader start (own rest, reversal)"
                k = out["kinds"].setdefault(kind_, [0, 0.0, 0])
                k[0] += 1
                k[1] += end[x] - start[x]
                # the plan itself stops the AGV here: a wait before the move (or its first move)
                k[2] += x not in prev or moves[x][3] - moves[prev[x]][3] > 1
                out["n_from_rest"] += 1
                node = ("start", x)
            else:
                out["events"].append(f"{start[x]:8.2f} agv{a_} {u_}->{v_} (step {t_}) chained, {end[x] - start[x]:.2f} s")
                out["chained"] += end[x] - start[x]
                on_path(a_, start[x], end[x])
                out["chained_least"] += 1 / vmax
                out["n_chained"] += 1
                node = ("end", prev[x]) if x in prev else None
        else:
            t0 = end[prev[x]] if x in prev else 0.0
            if h is not None and abs(start[h] - start[x]) <= tol and start[h] > t0 + 1e-9:
                # waited for the leader to start leaving: the path goes on through the leader's start
                out["events"].append(f"{start[x]:8.2f}   started with its leader agv{moves[h][0]} ({moves[h][1]}->{moves[h][2]})")
                node = ("start", h) if rested[h] else ("end", prev[h]) if h in prev else None
                continue
            out["rest"] += start[x] - t0
            on_path(moves[x][0], t0, start[x])
            rev = x in prev and moves[x][2] == moves[prev[x]][1]
            why = "rest_reversal" if rev else "rest_first" if x not in prev else \
                "rest_leader_started_before" if h is not None and start[h] < start[x] - tol else \
                "rest_leader_done_or_none"
            out[why] = out.get(why, 0) + start[x] - t0
            out["events"].append(f"{t0:8.2f}   agv{moves[x][0]} at rest {start[x] - t0:.2f} s ({why})")
            out["n_" + why] = out.get("n_" + why, 0) + 1
            node = ("end", prev[x]) if x in prev else None
    return out


def analyse(d, absorb=(0, 1, 2, 5)):
    cfg = open(os.path.join(d, "config.yaml")).read()
    acc, dec, vmax, dt = vtype(cfg)
    m = json.load(open(os.path.join(d, "metrics.json")))
    speeds = read_fcd(os.path.join(d, "fcd.xml"))
    rows = {vid: split_time(v, dt, acc, dec, vmax) for vid, v in speeds.items()}
    last = max(rows, key=lambda k: rows[k][0])
    tot = [sum(r[k] for r in rows.values()) for k in range(6)]
    shape = plan_shape(os.path.join(d, "plan.txt"))
    ex = re.search(r"\n  executor: ([\w-]+)", cfg).group(1)
    if ex == "lockstep":  # speeds jump within a step: no ramps, so stops cost nothing physically
        rows = {k: (r[0], r[1], 0.0, r[0] - r[1] - r[4], r[4], r[5]) for k, r in rows.items()}
        last = max(rows, key=lambda k: rows[k][0])
        tot = [sum(r[k] for r in rows.values()) for k in range(6)]
    trace = read_split_trace(os.path.join(d, "split_trace.txt"))
    exe = executed_path(os.path.join(d, "plan.txt"), speeds, dt, acc, dec, vmax, trace) if ex != "lockstep" else None
    crit = critical_path(os.path.join(d, "plan.txt"), acc, dec, vmax)
    crit_free = critical_path(os.path.join(d, "plan.txt"), acc, dec, vmax, free_reversals=True)
    kv = dict(x.strip().split(": ") for x in re.search(r"vtype: \{([^}]*)\}", cfg).group(1).split(","))
    gap = float(kv.get("length", 0.8)) + float(kv.get("min_gap", 0.1))
    crit_line = critical_path(os.path.join(d, "plan.txt"), acc, dec, vmax, gap=gap)
    crit_absorb = [(w, critical_path(os.path.join(d, "plan.txt"), acc, dec, vmax, gap=gap, absorb=w)) for w in absorb]
    return dict(run=os.path.basename(d.rstrip("/")), executor=ex, makespan=m["makespan"], solved=m["solved"],
                bound=m.get("bound_ticks"), last=last, last_row=rows[last], total=tot, shape=shape,
                time=m.get("executor", {}).get("time", {}), crit=crit, crit_free=crit_free,
                crit_line=crit_line, crit_absorb=crit_absorb, exe=exe)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--config", default="large_warehouse_agv.yaml")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--expansions", type=int, default=50)
    ap.add_argument("--window", type=int, default=16)
    ap.add_argument("--p", type=float, default=0.0, help="delay probability (bench_closed_loop.py's stops of 1-5 s); the bounds assume none")
    ap.add_argument("--max-ticks", type=int, default=1500)
    ap.add_argument("--executors", nargs="+", default=["lockstep", "adg-follow"])
    ap.add_argument("--out", default=None, help="folder for the runs (default: a temporary one)")
    ap.add_argument("--runs", nargs="+", default=None, help="analyse these run folders instead of running")
    ap.add_argument("--trace", type=int, default=0, help="print the last N events of the executed critical path")
    ap.add_argument("--absorb", nargs="*", type=float, default=[0, 1, 2, 5],
                    help="waits (s) an idealised executor absorbs without a stop (critical_path absorb=)")
    a = ap.parse_args()
    if a.runs:
        dirs = a.runs
    else:
        import tempfile
        base = a.out or tempfile.mkdtemp(prefix="decompose_")
        dirs = [make_run(a, ex, os.path.join(base, re.sub(r"[^\w.-]", "_", ex))) for ex in a.executors]
    res = [analyse(d, a.absorb) for d in dirs]
    print("Plans (plan.txt): steps, moves, longest path (moves), reversals, planned stops (waits between moves)\n")
    print("| run | executor | makespan | bound | plan steps | moves | longest | reversals | planned stops |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in res:
        s = r["shape"]
        print(f"| {r['run']} | {r['executor']} | {r['makespan']} | {r['bound']} | {s[0]} | {s[1]} | {s[2]} | {s[3]} | {s[4]} |")
    print("\nTime to the last arrival, s (from fcd): distance at top speed + ramps of the stops + slowdown in motion"
          " + rest; stops = motion segments\n")
    print("| run | who | arrival | distance | ramps | slowdown | rest | stops |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for r in res:
        for who, row in ((f"last ({r['last']})", r["last_row"]), ("fleet sum", r["total"])):
            print(f"| {r['run']} | {who} | {row[0]:.1f} | {row[1]:.1f} | {row[2]:.1f} | {row[3]:.1f} | {row[4]:.1f} | {row[5]} |")
    print("\nShares of the fleet's time (sum over AGVs to their last arrival):\n")
    print("| run | distance | ramps | slowdown | rest | s per move | stops per move |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for r in res:
        t = r["total"]
        print(f"| {r['run']} | {t[1] / t[0]:.3f} | {t[2] / t[0]:.3f} | {t[3] / t[0]:.3f} | {t[4] / t[0]:.3f} | "
              f"{t[0] / max(1, r['shape'][1]):.3f} | {t[5] / max(1, r['shape'][1]):.3f} |")
    print("\nThe plan's ADG critical path with each move's least physical time (a lower bound for any ADG"
          " executor on this plan), s; on it: moves (from rest / to rest), hand-over links; the same with"
          " reversals free (no rest); and with the line model of adg-follow and Safety (a front reaches v once"
          " its leader's front is length + min_gap past v: critical_path(gap=)), a bound for adg-follow that"
          " charges no stop the anticipation could avoid\n")
    print("| run | makespan | critical path | moves | from rest | to rest | links | makespan / path |"
          " path, reversals free | path, line model | makespan / line path |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in res:
        c, f, g = r["crit"], r["crit_free"], r["crit_line"]
        print(f"| {r['run']} | {r['makespan']} | {c[0]:.1f} | {c[3]} | {c[1]} | {c[2]} | {c[4]} | "
              f"{r['makespan'] / c[0]:.3f} | {f[0]:.1f} | {g[0]:.1f} | {r['makespan'] / g[0]:.3f} |")
    if a.absorb:
        print("\nThe line-model path for an idealised executor that absorbs a wait of up to W s without a stop (it"
              " rolls in slower, for free) and stops for a longer one (standing, then a move from rest once released):"
              " how far anticipation would have to reach; s (stops on the path)\n")
        print("| run | makespan | " + " | ".join(f"W = {w:g} s" for w in a.absorb) + " | W = inf (line model) |")
        print("|---|---:|" + "---:|" * (len(a.absorb) + 1))
        for r in res:
            print(f"| {r['run']} | {r['makespan']} | " +
                  " | ".join(f"{c[0]:.1f} ({c[5]})" for _, c in r["crit_absorb"]) + f" | {r['crit_line'][0]:.1f} |")
    print("\nThe executed critical path (physical executors), s: back from the last arrival through the constraint met"
          " last; moves from rest and chained (their least time in brackets), rests not spent waiting for a"
          " leader's start (before a reversal: the AGV must stop), links (arrivals in ADG order)\n")
    print("| run | from rest (least) | n | chained (least) | n | rest before reversals | other rests | links |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in res:
        e = r["exe"]
        if e:
            print(f"| {r['run']} | {e['from_rest']:.1f} ({e['from_rest_least']:.1f}) | {e['n_from_rest']} | "
                  f"{e['chained']:.1f} ({e['chained_least']:.1f}) | {e['n_chained']} | {e.get('rest_reversal', 0):.1f} | "
                  f"{e['rest'] - e.get('rest_reversal', 0):.1f} | {e['links']} |")
    for r in res:
        e = r["exe"]
        if e and e.get("cycles"):
            print(f"\n{r['run']}: the path was cut at {e['events'][-1].split()[0]} s, at a cycle of hand-overs (a "
                  f"rotation within one plan step); the table covers the path after that only")
    print("\nThe moves from rest on the executed critical path: how long each AGV stood before it started (since its"
          " previous move ended): short stands are stops a rolling approach could have saved\n")
    bins = [(0, 0.5), (0.5, 1), (1, 2), (2, 5), (5, math.inf)]
    print("| run | n | median s | " + " | ".join(f"{lo}-{hi} s" for lo, hi in bins) + " |")
    print("|---|---:|---:|" + "---:|" * len(bins))
    for r in res:
        st = sorted(r["exe"]["stood"]) if r["exe"] else []
        if st:
            print(f"| {r['run']} | {len(st)} | {st[len(st) // 2]:.2f} | " +
                  " | ".join(str(sum(1 for w in st if lo <= w < hi)) for lo, hi in bins) + " |")
    print("\nThe moves from rest on the executed critical path by what the AGV waited for: its leader's start with"
          " the follower entering on the leader's line out of the cell (train start) or from another side (a"
          " junction passage), or no leader (its own rest: a reversal, a first move)\n")
    print("| run | kind | n | s | s per move | of them planned stops (a wait in plan.txt before the move) |")
    print("|---|---|---:|---:|---:|---:|")
    for r in res:
        for kind, (cnt, sec, planned) in sorted((r["exe"] or {}).get("kinds", {}).items()):
            print(f"| {r['run']} | {kind} | {cnt} | {sec:.1f} | {sec / cnt:.2f} | {planned} |")
    if any(r["exe"] and r["exe"]["cats"] for r in res):
        print("\nThe executed critical path by the Driver's category of each SUMO step on it (split_trace.txt;"
              " controller/driver.hpp DriveStats::Split), s\n")
        for r in res:
            if r["exe"] and r["exe"]["cats"]:
                c = r["exe"]["cats"]
                lost = r["exe"]["lost"]
                print(f"| {r['run']} | " + ", ".join(f"{k} {v:.1f} ({lost.get(k, 0):.1f} lost)"
                                                    for k, v in sorted(c.items(), key=lambda kv: -kv[1]))
                      + f" | total {sum(c.values()):.1f} ({sum(lost.values()):.1f} lost against top speed) |")
    if a.trace:
        for r in res:
            if r["exe"]:
                print(f"\n{r['run']}: the executed critical path, last {a.trace} events (time s, forward)")
                for line in reversed(r["exe"]["events"][:a.trace]):
                    print(line)
    for r in res:
        if r["time"]:
            print(f"\n{r['run']}: executor agent-steps by what bounds the speed (metrics.json executor.time): {r['time']}")


if __name__ == "__main__":
    main()
