#!/usr/bin/env python3
"""How far above the lower bound is the optimum of a small one-shot SUMO instance?

Exports the instance of a controller run (starts/goals from its plan.txt, the cells from
`rtlacam-gridify --map`) as a MovingAI .scen, and prints a pairwise lower bound on the
optimal SOC (LaCAM* cost: 1 per agent per action, 0 while staying on the goal): for every
pair of agents the exact 2-agent optimum (Dijkstra over joint positions, no vertex or swap
conflict), then the best matching of disjoint pairs. Valid because the optimal plan
restricted to two agents is a 2-agent plan of the same cost. Small instances only
(|V|^2 states per pair, 2^N matching DP).

  ./build/apps/rtlacam-gridify sumo_scenarios/small.net.xml --additional sumo_scenarios/small.add.xml --map out/small.map
  ./build/apps/rtlacam-sumo config/small_warehouse.yaml
  python3 scripts/demo_pair_bound.py out/small_warehouse/plan.txt out/small.map out/small.scen
  ./build/apps/rtlacam-bench --map out/small.map --scen out/small.scen -N 16 --solver lacam --refine --anytime-ms 3000 --seed S
"""
import heapq, itertools, os, re, sys
from functools import lru_cache

plan, mp, sc = sys.argv[1], sys.argv[2], sys.argv[3]
t = open(plan).read()
P = lambda k: [tuple(map(int, m)) for m in re.findall(r'\((\d+),(\d+)\)', re.search('^' + k + '=(.*)$', t, re.M).group(1))]
rows0 = open(mp).read().split('map\n')[1].split()
with open(sc, 'w') as f:
    f.write('version 1\n')
    for a, b in zip(P('starts'), P('goals')):
        f.write(f"0\t{os.path.basename(mp)}\t{len(rows0[0])}\t{len(rows0)}\t{a[0]}\t{a[1]}\t{b[0]}\t{b[1]}\t0\n")
rows = open(mp).read().split('map\n')[1].split()
H, W = len(rows), len(rows[0])
cells = [(x, y) for y in range(H) for x in range(W) if rows[y][x] == '.']
idx = {c: i for i, c in enumerate(cells)}
nb = [[idx[(x+dx, y+dy)] for dx, dy in ((1,0),(-1,0),(0,1),(0,-1)) if (x+dx, y+dy) in idx] for (x, y) in cells]
ag = []
for l in open(sc).read().split('\n')[1:]:
    if not l.strip(): continue
    f = l.split('\t'); ag.append((idx[(int(f[4]), int(f[5]))], idx[(int(f[6]), int(f[7]))]))
n = len(ag)
def bfs(s):
    d = [10**9]*len(cells); d[s] = 0; q = [s]
    for v in q:
        for u in nb[v]:
            if d[u] > d[v]+1: d[u] = d[v]+1; q.append(u)
    return d
dist = [bfs(g) for s, g in ag]
lb = sum(dist[i][ag[i][0]] for i in range(n))
def pair(i, j):
    (s1, g1), (s2, g2) = ag[i], ag[j]
    best = {(s1, s2): 0}; pq = [(0, s1, s2)]
    while pq:
        c, a, b = heapq.heappop(pq)
        if best[(a, b)] < c: continue
        if (a, b) == (g1, g2): return c
        for u in nb[a] + [a]:
            for w in nb[b] + [b]:
                if u == w or (u == b and w == a): continue
                nc = c + (not (a == g1 and u == g1)) + (not (b == g2 and w == g2))
                if nc < best.get((u, w), 10**9): best[(u, w)] = nc; heapq.heappush(pq, (nc, u, w))
    return None
gain = {}
for i, j in itertools.combinations(range(n), 2):
    gain[(i, j)] = pair(i, j) - dist[i][ag[i][0]] - dist[j][ag[j][0]]
@lru_cache(None)
def best(mask):  # max matching gain over agents not in mask
    i = next((k for k in range(n) if not mask >> k & 1), None)
    if i is None: return 0
    r = best(mask | 1 << i)
    for j in range(i+1, n):
        if not mask >> j & 1: r = max(r, gain[(i, j)] + best(mask | 1 << i | 1 << j))
    return r
m = best(0)
print('cells', len(cells), 'agents', n, 'LB (sum of distances)', lb)
print('pairs with a surplus:', sorted(((v, k) for k, v in gain.items() if v > 0), reverse=True))
print('pairwise matching bound', lb + m, 'ratio', round((lb + m) / lb, 3))
