#!/usr/bin/env python3
"""Collision-free upper bound on errands/step for a LoRR 2023 roundrobin problem, rotation model.

Each robot alone on the map (no other robot in its way) works through its own errand
sequence (agent a gets tasks a, a + n, a + 2n, ...: roundrobin), moving along shortest paths
of LoRR's MAPF_T model (forward, quarter turns; all robots start facing east), for the
problem's number of steps. The sum of the errands finished, per step, bounds what any planner
can reach on that problem: what a planner loses against it is interference between robots.

Two variants of the heading a robot reaches each goal with (it starts the next errand facing
that way): `worst` takes, among the shortest paths, the arrival heading worst for the next
errand; `hindsight` picks arrival headings knowing every later errand (dynamic programming,
also over longer paths). Their gap is the most an arrival-heading rule can gain.

    python3 scripts/lorr_free_flow_bound.py ../shared/benchmarks/lorr/2023/random.domain/MR23-I-04.json

Python 3, stdlib only; about 40 s for 100 robots over 500 steps on random-32-32-20.
"""
import argparse
import collections
import functools
import json
import os
import sys

DIRS = [(0, 1), (1, 0), (0, -1), (-1, 0)]  # east, south, west, north as (row, column)


def read_ids(path):
    vals = [int(x) for line in open(path) if not line.startswith("#") for x in line.split(",") if x.strip()]
    return vals[1:]  # the first number is the count


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("problem", help="LoRR 2023 problem JSON (roundrobin)")
    ap.add_argument("--steps", type=int, help="default: simulation_time.json beside or above the problem")
    a = ap.parse_args()
    base = os.path.dirname(os.path.abspath(a.problem))
    p = json.load(open(a.problem))
    if p.get("taskAssignmentStrategy") != "roundrobin":
        sys.exit(f"{a.problem}: not a roundrobin problem")
    steps = a.steps
    if steps is None:
        key = os.path.basename(a.problem).split(".")[0].replace("MR23-", "")
        for d in (base, os.path.dirname(base)):
            f = os.path.join(d, "simulation_time.json")
            if os.path.exists(f):
                steps = json.load(open(f)).get(key)
                break
        if steps is None:
            sys.exit(f"{a.problem}: no simulation_time.json entry: pass --steps")
    lines = open(os.path.join(base, p["mapFile"])).read().split("\n")
    h, w = int(lines[1].split()[1]), int(lines[2].split()[1])
    grid = lines[4:4 + h]
    n = p["teamSize"]
    agents = read_ids(os.path.join(base, p["agentFile"]))[:n]
    tasks = read_ids(os.path.join(base, p["taskFile"]))

    def free(c):
        return 0 <= c[0] < h and 0 <= c[1] < w and grid[c[0]][c[1]] not in "@T"

    # Both passes ask for the same searches (and the worst pass asks for each next errand's
    # twice): one BFS per (cell, heading, goal).
    @functools.lru_cache(maxsize=None)
    def arrivals(v, o, goal):
        """Fewest steps from (v, o) to first stand on goal, per arrival heading."""
        if v == goal:
            return {o: 0}
        dist = {(v, o): 0}
        q = collections.deque([(v, o)])
        out = {}
        while q:
            s = q.popleft()
            u, oo = s
            if u == goal:
                continue
            ahead = (u[0] + DIRS[oo][0], u[1] + DIRS[oo][1])
            for nxt in ((u, (oo + 1) % 4), (u, (oo + 3) % 4), (ahead, oo)):
                if free(nxt[0]) and nxt not in dist:
                    dist[nxt] = dist[s] + 1
                    if nxt[0] == goal:
                        out[nxt[1]] = dist[nxt]
                    q.append(nxt)
        if not out:
            sys.exit(f"{a.problem}: errand cell (row {goal[0]}, column {goal[1]}) cannot be reached from "
                     f"(row {v[0]}, column {v[1]})")
        return out

    cell = lambda i: (i // w, i % w)
    hind = worst = 0
    for r in range(n):
        seq = [cell(tasks[(r + k * n) % len(tasks)]) for k in range(steps + 1)]
        # hindsight: per arrival heading, the earliest time k errands are done
        pos, states = cell(agents[r]), {0: 0}
        for goal in seq:
            nxt = {}
            for o, t in states.items():
                for o2, d in arrivals(pos, o, goal).items():
                    nxt[o2] = min(nxt.get(o2, 1 << 30), t + d)
            if min(nxt.values()) > steps:
                break
            hind += 1
            pos, states = goal, {o: t for o, t in nxt.items() if t <= steps}
        # worst shortest-path arrival heading (by the next errand's distance)
        pos, o, t = cell(agents[r]), 0, 0
        for k, goal in enumerate(seq):
            ar = arrivals(pos, o, goal)
            best = min(ar.values())
            nxt_goal = seq[k + 1] if k + 1 < len(seq) else goal
            o2 = max((x for x in ar if ar[x] == best), key=lambda x: min(arrivals(goal, x, nxt_goal).values()))
            t += best
            if t > steps:
                break
            worst += 1
            pos, o = goal, o2
        print(f"\r{r + 1}/{n} robots", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    print(json.dumps({"problem": a.problem, "agents": n, "steps": steps,
                      "hindsightErrandsPerStep": hind / steps, "worstHeadingErrandsPerStep": worst / steps}))


if __name__ == "__main__":
    main()
