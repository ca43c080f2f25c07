#!/usr/bin/env python3
"""Why a lifelong SUMO run decays: read a finished run's outputs (no rerun).

Reads RUN/lifelong.json (errand events: [tick, agent, task, errand#]), RUN/plan.txt (the
executed plan, one configuration per committed plan step; its steps are not ticks) and the
gridify json of the net (cells, edges, stations; bench_twin.py writes it under
twin_<config>/). Prints, per window of ticks:
  - errands, the AGVs that finished one (active), the task holders stalled (no errand
    finished for > 300 / 600 / 1000 ticks: a stall longer than the run's errands ever need);
  - errands per active AGV (is the decay fewer workers, or slower ones?);
and, at the end of the plan:
  - every AGV stalled > --stuck ticks: its next errand, where it stands, the nearest station,
    how much it still moves in the plan (a livelock moves, a deadlock does not);
  - each station cell's occupants over the last plan steps (task holder or idle AGV).
Only the AGVs that finished an errand count as task holders (pool admission keeps the rest
idle all run on the shipped queues configs). stdlib only.

  scripts/lifelong_decay.py OUT/huge_..._p0 OUT/twin_huge_warehouse_lifelong/huge_warehouse_lifelong.grid.json
"""
import argparse, collections, json, re
from collections import deque


def load_plan(path, cid):
    rows, on = [], False
    with open(path) as f:
        for line in f:
            if line.startswith('solution='):
                on = True
                continue
            if not on:
                continue
            _, _, rest = line.partition(':')
            if rest:
                rows.append([cid[(int(a), int(b))] for a, b in re.findall(r'\((\d+),(\d+)\)', rest)])
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('run', help='output dir of one rtlacam-sumo lifelong run')
    ap.add_argument('grid', help='rtlacam-gridify json of the same net')
    ap.add_argument('--window', type=int, default=500, help='ticks per window (500)')
    ap.add_argument('--stuck', type=int, default=1000, help='list task holders stalled this long at the end (1000)')
    ap.add_argument('--tail', type=int, default=500, help='plan steps read for station occupants (500)')
    a = ap.parse_args()

    g = json.load(open(a.grid))
    cells = g['cells']
    n = len(cells)
    adj = [[] for _ in range(n)]
    for u, v in g['edges']:
        adj[u].append(v)
        adj[v].append(u)
    station = {s['cell']: s['id'] for s in g['stations']}
    L = json.load(open(a.run + '/lifelong.json'))
    ev = L['events']
    ticks = L.get('makespan', max(e[0] for e in ev))
    by = collections.defaultdict(list)
    for e in ev:
        by[e[1]].append(e)
    holders = sorted(by)
    print(f'{a.run}: {len(ev)} errands, {len(holders)} AGVs ever finished one (of {L["teamSize"]}), '
          f'idle at end {L["parking"]["idleAtEnd"]}')
    print('tick_end errands active stalled>300 >600 >1000 errands/active')
    for T in range(a.window, ticks + 1, a.window):
        win = [e for e in ev if T - a.window < e[0] <= T]
        act = len(set(e[1] for e in win))
        gaps = [T - max([e[0] for e in by[x] if e[0] <= T], default=0) for x in holders]
        s = [sum(gp > k for gp in gaps) for k in (300, 600, 1000)]
        print(f'{T:8d} {len(win):7d} {act:6d} {s[0]:11d} {s[1]:4d} {s[2]:5d} {len(win) / max(1, act):14.2f}')

    cid = {(c['col'], c['row']): c['id'] for c in cells}
    P = load_plan(a.run + '/plan.txt', cid)
    S = len(P)
    print(f'plan: {S} committed steps for {ticks} ticks')

    def bfs(s):
        d = [-1] * n
        d[s] = 0
        q = deque([s])
        while q:
            u = q.popleft()
            for v in adj[u]:
                if d[v] < 0:
                    d[v] = d[u] + 1
                    q.append(v)
        return d

    stuck = sorted((x for x in holders if ticks - by[x][-1][0] > a.stuck), key=lambda x: by[x][-1][0])
    tail = range(max(0, S - a.tail), S - 1)
    print(f'task holders stalled > {a.stuck} ticks at the end: {len(stuck)}')
    near_count = collections.Counter()
    for x in stuck:
        last = by[x][-1]
        c = P[-1][x]
        d = bfs(c)
        dist, sid = min((d[s], i) for s, i in station.items() if d[s] >= 0)
        near_count[sid] += 1
        mv = sum(P[s][x] != P[s + 1][x] for s in tail)
        print(f'  agent {x}: last errand t={last[0]} (errand {last[3]}), cell ({cells[c]["col"]},{cells[c]["row"]}) '
              f'{cells[c]["kind"]}, {dist} cells from {sid}; moves in the last {len(tail)} plan steps: {mv}')
    print('  nearest station of the stalled ones:', dict(near_count.most_common()))
    hs = set(holders)
    print(f'station cells held > half of the last {len(tail) + 1} plan steps by one AGV:')
    for sc, sid in sorted(station.items(), key=lambda kv: kv[1]):
        occ = collections.Counter(P[s].index(sc) for s in range(max(0, S - a.tail), S) if sc in P[s])
        for x, k in occ.most_common(1):
            if 2 * k > len(tail) + 1:
                print(f'  {sid} (degree {len(adj[sc])}): agent {x} ({"task holder" if x in hs else "idle"}) {k} steps')


if __name__ == '__main__':
    main()
