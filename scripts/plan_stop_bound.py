#!/usr/bin/env python3
"""What the planned stops cost under physics (issue 21, the 1.25x target at p = 0).

Reads a run's plan.txt (one configuration per plan step, cells as (x, y) lattice points) and,
per AGV alone on its planned path with the vType's kinematics (controller/bound.hpp's
rest_to_rest_s), prints three times:

  flow     the physical bound (metrics.json plan_bound_ticks): waits dropped, one trapezoid per
           straight stretch between reversals (a reversal rests one SUMO step);
  stops    the same path, but the AGV comes to rest at every planned wait too: each stretch
           between two waits (or reversals) is its own trapezoid;
  timed    stops + one tick at rest per planned wait step: a physical AGV that keeps the
           lockstep plan's waits as they are, each a stop of one tick.

and, against the plan's lockstep time (moves + waits, in ticks, = lockstep's makespan for a
lockstep plan), the ratios. A plan executed with its waits kept (strict timing) costs at
least `timed`; an executor that flows through a planned wait saves that stop only when the
dependency behind the wait is already met, which congestion rarely allows.

  scripts/plan_stop_bound.py OUT/plan.txt [--cell 1.0] [--accel 0.5] [--decel 1.0]
                             [--vmax 1.0] [--dt 0.125] [--tick 1.0]
"""
import argparse
import math
import re


def rest_to_rest_s(L, a, d, V):
    if L <= 0:
        return 0.0
    ramps = V * V / (2 * a) + V * V / (2 * d)
    if L >= ramps:
        return L / V + V / (2 * a) + V / (2 * d)
    peak = math.sqrt(2 * L * a * d / (a + d))
    return peak / a + peak / d


def read_plan(path):
    steps = []
    cell = re.compile(r"\((-?\d+),(-?\d+)\)")
    with open(path) as f:
        for line in f:
            m = re.match(r"^(\d+):(.*)$", line)
            if m:
                steps.append([(int(x), int(y)) for x, y in cell.findall(m.group(2))])
    return steps


def per_agent(steps, cell, a, d, V, dt, tick):
    n = len(steps[0])
    out = []
    for i in range(n):
        path = [s[i] for s in steps]
        last_move = max((t for t in range(1, len(path)) if path[t] != path[t - 1]), default=0)
        flow = stops = 0.0
        f_len = s_len = 0.0  # metres of the open stretch: flow (waits dropped), stops (split at waits)
        waits = moves = stop_count = 0
        before = path[0]
        for t in range(1, last_move + 1):
            u, v = path[t - 1], path[t]
            if u == v:
                waits += 1
                if s_len > 0:  # the AGV comes to rest here
                    stops += rest_to_rest_s(s_len, a, d, V)
                    s_len = 0.0
                    stop_count += 1
                continue
            moves += 1
            if v == before and before != u:  # reverses: both rest and turn in place
                flow += rest_to_rest_s(f_len, a, d, V) + dt
                stops += rest_to_rest_s(s_len, a, d, V) + dt
                f_len = s_len = 0.0
            m = cell * math.hypot(v[0] - u[0], v[1] - u[1])
            f_len += m
            s_len += m
            before = u
        flow += rest_to_rest_s(f_len, a, d, V)
        stops += rest_to_rest_s(s_len, a, d, V)
        out.append(dict(flow=flow / tick, stops=stops / tick, timed=(stops + waits * tick) / tick,
                        lockstep=moves + waits, moves=moves, waits=waits, stop_count=stop_count))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("plan")
    ap.add_argument("--cell", type=float, default=1.0)
    ap.add_argument("--accel", type=float, default=0.5)
    ap.add_argument("--decel", type=float, default=1.0)
    ap.add_argument("--vmax", type=float, default=1.0)
    ap.add_argument("--dt", type=float, default=0.125)
    ap.add_argument("--tick", type=float, default=1.0)
    a = ap.parse_args()
    steps = read_plan(a.plan)
    rows = per_agent(steps, a.cell, a.accel, a.decel, a.vmax, a.dt, a.tick)
    mx = {k: max(r[k] for r in rows) for k in ("flow", "stops", "timed", "lockstep", "moves")}
    tot = {k: sum(r[k] for r in rows) for k in ("moves", "waits", "stop_count")}
    print(f"plan {a.plan}: {len(rows)} AGVs, {len(steps) - 1} plan steps; moves {tot['moves']}, "
          f"waits before the last move {tot['waits']}, stops (a wait after a move) {tot['stop_count']}")
    print("| bound (ticks, max over AGVs) | value | over flow |\n|---|---:|---:|")
    print(f"| lockstep: moves (its bound) | {mx['moves']} | - |")
    print(f"| lockstep: moves + waits (plan time) | {mx['lockstep']} | - |")
    for k in ("flow", "stops", "timed"):
        print(f"| physics {k} | {mx[k]:.1f} | {mx[k] / mx['flow']:.3f} |")
    print(f"lockstep plan time / its bound: {mx['lockstep'] / mx['moves']:.3f}; physics timed / flow: "
          f"{mx['timed'] / mx['flow']:.3f}; ratio of the two: {(mx['timed'] / mx['flow']) / (mx['lockstep'] / mx['moves']):.3f}")


if __name__ == "__main__":
    main()
