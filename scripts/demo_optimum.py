#!/usr/bin/env python3
"""Exact optimum of a small one-shot MAPF instance (the default SUMO demo) by SAT.

MDD-SAT style (Surynek et al.): for a slack D, is there a plan of cost <= LB + D?
LB = sum of BFS distances. Each agent i gets a Boolean x[i,v,t] for every (v,t) it can use
in a plan of its own cost <= d_i + D (d_i = dist(s_i, g_i)); horizon T = max_i d_i + D.
Clauses: start and goal units; every true x has a true successor (stay or an edge) and a
true predecessor; at most one agent per (v,t) (vertex conflicts); at most one agent crosses
an edge {u,v} between t and t+1 (swap conflicts; two crossing it the same way would collide
at t+1 anyway); following is allowed. A totalizer bounds the agents' total delay by D.
Two costs (--cost):
  loss  the validator's and the controller's SOC (planner/src/validator.cpp: every
        transition costs 1 per agent except staying on its goal; lacam3's sum_of_loss).
        Agent i's delay literals: c_i(t) = "not (at g_i at t and at t+1)" for t >= d_i.
        An agent may reach its goal, wait there free and leave again, so T = max d + D
        is the bound on the makespan (every step before all are home costs >= 1 beyond
        the sum of distances), not on the agents' own costs.
  soc   classic SOC: per agent the time of its last arrival at its goal (EECBS, CBS).
        finished_i(t) -> at(g_i, t) and finished_i(t+1); delay literals not finished_i(t)
        for t in d_i .. d_i + D - 1.
loss <= soc on every plan, so loss-UNSAT at D proves soc-UNSAT at D, soc-SAT proves loss-SAT.
Cost literals are forced by every vertex off the goal (not by "not at goal"), so a decoded
path (follow true successors from the start) pays at most what the counter counted.

Solver: CaDiCaL's CLI (DIMACS in, exit 10 SAT / 20 UNSAT), `apt-get install cadical`.
Not a project dependency (offline measurement tool, not in scripts/install-deps.sh).
Decoded plans are checked with the project's validator through the Python bindings
(build/python, `import rtlacam`: validate_plan and Validator.sum_of_costs) when importable,
else with the script's own check; --plan-out writes the plan in plan_io's result format.

  python3 scripts/demo_optimum.py --self-check                     # vs exhaustive search
  python3 scripts/demo_optimum.py out/small.map out/small.scen --cost loss --target 210
  python3 scripts/demo_optimum.py out/small.map out/small.scen --cost loss --minimise --lo 201 --hi 243
"""
import argparse, heapq, itertools, os, random, re, subprocess, sys, tempfile, time

# ---------------------------------------------------------------- instance


class Grid:
    def __init__(self, rows):
        self.rows = rows
        self.h, self.w = len(rows), len(rows[0])
        self.cells = [(x, y) for y in range(self.h) for x in range(self.w) if rows[y][x] in '.GSE']
        self.idx = {c: i for i, c in enumerate(self.cells)}
        self.nb = [[self.idx[(x + dx, y + dy)] for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
                    if (x + dx, y + dy) in self.idx] for (x, y) in self.cells]

    def bfs(self, s):
        d = [None] * len(self.cells)
        d[s] = 0
        q = [s]
        for v in q:
            for u in self.nb[v]:
                if d[u] is None:
                    d[u] = d[v] + 1
                    q.append(u)
        return d


def load(map_path, scen_path, n):
    lines = open(map_path).read().split('\n')
    k = lines.index('map')
    h = int(lines[1].split()[1])
    g = Grid([l for l in lines[k + 1:k + 1 + h]])
    starts, goals = [], []
    for ln, l in enumerate(open(scen_path).read().split('\n')[1:], 2):
        if not l.strip() or len(starts) == n: continue
        f = l.split('\t')
        s, t = (int(f[4]), int(f[5])), (int(f[6]), int(f[7]))
        for c in (s, t):
            if c not in g.idx: sys.exit(f'{scen_path}:{ln}: cell {c} is not free on {map_path}')
        starts.append(g.idx[s])
        goals.append(g.idx[t])
    if len(starts) < n: sys.exit(f'{scen_path}: {len(starts)} agents, {n} asked')
    return g, starts, goals

# ---------------------------------------------------------------- encoding


class Cnf:
    def __init__(self):
        self.n, self.cl = 0, []

    def var(self):
        self.n += 1
        return self.n

    def add(self, *lits):
        self.cl.append(lits)

    def amo(self, lits):  # at most one: pairwise when small, else sequential (Sinz)
        if len(lits) <= 5:
            for a, b in itertools.combinations(lits, 2): self.add(-a, -b)
            return
        s = [self.var() for _ in lits[:-1]]
        for k, x in enumerate(lits):
            if k < len(s): self.add(-x, s[k])
            if k > 0: self.add(-x, -s[k - 1])
            if 0 < k < len(s): self.add(-s[k - 1], s[k])

    def merge(self, a, b, k):  # totalizer node: unary a + b, outputs capped at k + 1 (r[j]: sum > j)
        r = [self.var() for _ in range(min(len(a) + len(b), k + 1))]
        for i in range(len(a) + 1):
            for j in range(len(b) + 1):
                if 1 <= i + j <= len(r):
                    self.add(*([-a[i - 1]] if i else []), *([-b[j - 1]] if j else []), r[i + j - 1])
        return r

    def count(self, units, k):  # merges unary numbers (lists of literals) into one, capped at k + 1
        if not units: return []
        if len(units) == 1: return units[0]
        h = len(units) // 2
        return self.merge(self.count(units[:h], k), self.count(units[h:], k), k)

    def at_most(self, out, k):
        if len(out) > k: self.add(-out[k])

    def dimacs(self, path):
        with open(path, 'w') as f:
            f.write(f'p cnf {self.n} {len(self.cl)}\n')
            f.write(''.join(' '.join(map(str, c)) + ' 0\n' for c in self.cl))


def pair_surplus(g, starts, goals):
    """Exact 2-agent loss optimum minus the two distances, for every pair (as
    demo_pair_bound.py): a lower bound on delay_i + delay_j in any plan, for both costs
    (soc >= loss)."""
    n = len(starts)
    dg = [g.bfs(t) for t in goals]
    out = {}
    for i, j in itertools.combinations(range(n), 2):
        (s1, g1), (s2, g2) = (starts[i], goals[i]), (starts[j], goals[j])
        best = {(s1, s2): 0}
        pq = [(0, s1, s2)]
        c = None
        while pq:
            c, a, b = heapq.heappop(pq)
            if best[(a, b)] < c: continue
            if (a, b) == (g1, g2): break
            for u in g.nb[a] + [a]:
                for w in g.nb[b] + [b]:
                    if u == w or (u == b and w == a): continue
                    nc = c + (not (a == g1 and u == g1)) + (not (b == g2 and w == g2))
                    if nc < best.get((u, w), 1 << 60):
                        best[(u, w)] = nc
                        heapq.heappush(pq, (nc, u, w))
        sur = c - dg[i][s1] - dg[j][s2]
        if sur > 0: out[(i, j)] = sur
    return out


def matching_bounds(n, sur):
    """Best matching of disjoint pairs: M[i] = bound on the delay of all agents but i
    (M[n] = of all)."""
    memo = {}

    def best(mask):
        if mask in memo: return memo[mask]
        i = next((k for k in range(n) if not mask >> k & 1), None)
        r = 0
        if i is not None:
            r = best(mask | 1 << i)
            for j in range(i + 1, n):
                if not mask >> j & 1 and (i, j) in sur: r = max(r, sur[(i, j)] + best(mask | 1 << i | 1 << j))
        memo[mask] = r
        return r
    return [best(1 << i) for i in range(n)] + [best(0)]


def encode(g, starts, goals, D, cost, sur=None):
    """sur: pair surpluses (pair_surplus): agent i's own slack is D minus the others' matching
    bound, and every pair's delays are bounded below by clauses on per-agent counters."""
    n = len(starts)
    sur = sur or {}
    M = matching_bounds(n, sur)
    if M[n] > D: return 'UNSAT'  # the pair matching bound alone
    dg = [g.bfs(t) for t in goals]
    ds = [g.bfs(s) for s in starts]
    d = [dg[i][starts[i]] for i in range(n)]
    if any(x is None for x in d): return None  # some goal unreachable
    T = max(d) + D
    cnf = Cnf()
    x = []  # x[i][(v, t)] -> var
    for i in range(n):
        xi = {}
        for t in range(T + 1):
            for v in range(len(g.cells)):
                if ds[i][v] is None or ds[i][v] > t or dg[i][v] > T - t: continue
                if cost == 'soc':
                    lbi = d[i] if v == goals[i] else t + dg[i][v]
                else:  # loss: free goal waits before t, if it fits (min cost to be at v at t) + rest
                    lbi = min(t, d[i] + dg[i][v]) + dg[i][v]
                if lbi <= d[i] + D - M[i]: xi[(v, t)] = cnf.var()
        x.append(xi)
    for i in range(n):
        xi = x[i]
        cnf.add(xi[(starts[i], 0)])
        cnf.add(xi[(goals[i], T)])
        for (v, t), a in xi.items():
            if t < T: cnf.add(-a, *[xi[(w, t + 1)] for w in g.nb[v] + [v] if (w, t + 1) in xi])
            if t > 0: cnf.add(-a, *[xi[(u, t - 1)] for u in g.nb[v] + [v] if (u, t - 1) in xi])
    for t in range(T + 1):  # vertex conflicts
        for v in range(len(g.cells)):
            cnf.amo([x[i][(v, t)] for i in range(n) if (v, t) in x[i]])
    for t in range(T):  # swap conflicts: one agent per edge per step
        for u in range(len(g.cells)):
            for v in g.nb[u]:
                if v < u: continue
                es = []
                for i in range(n):
                    for a, b in ((u, v), (v, u)):
                        if (a, t) in x[i] and (b, t + 1) in x[i]:
                            e = cnf.var()
                            cnf.add(-x[i][(a, t)], -x[i][(b, t + 1)], e)
                            es.append(e)
                cnf.amo(es)
    per = []  # per agent: unary delay counter
    for i in range(n):
        xi, gi, Di = x[i], goals[i], D - M[i]
        delay = []
        if cost == 'loss':
            for t in range(d[i], T):
                c = cnf.var()
                for (v, tt), a in xi.items():
                    if v != gi and tt in (t, t + 1): cnf.add(-a, c)
                delay.append(c)
        else:
            fin = {}
            for t in range(d[i], d[i] + Di): fin[t] = cnf.var()
            for t, f in fin.items():
                cnf.add(-f, xi[(gi, t)])
                if t + 1 in fin: cnf.add(-f, fin[t + 1])
                for (v, tt), a in xi.items():
                    if tt == t and v != gi: cnf.add(-f, -a)
                delay.append(-f)
        per.append(cnf.count([[l] for l in delay], Di))
        cnf.at_most(per[-1], Di)
    for (i, j), sv in sur.items():  # delay_i + delay_j >= sv
        for a in range(sv):  # delay_i > a or delay_j > sv - 1 - a
            cl = [o[k] for o, k in ((per[i], a), (per[j], sv - 1 - a)) if k < len(o)]
            cnf.add(*cl)
    cnf.at_most(cnf.count(per, D), D)
    return cnf, x, T, sum(d)


def decode(g, starts, goals, x, T, model):
    plan = [list(starts)]
    for t in range(T):
        nxt = []
        for i, v in enumerate(plan[-1]):
            w = next(w for w in g.nb[v] + [v] if (w, t + 1) in x[i] and model.get(x[i][(w, t + 1)]))
            nxt.append(w)
        plan.append(nxt)
    while len(plan) > 1 and plan[-2] == goals: plan.pop()
    return plan


def solve(cnf, timeout_s, keep=None):
    with tempfile.TemporaryDirectory() as tmp:
        path = keep or os.path.join(tmp, 'f.cnf')
        cnf.dimacs(path)
        t0 = time.time()
        cmd = ['cadical', '-q', path] if timeout_s is None else ['cadical', '-t', str(int(timeout_s)), path]
        p = subprocess.run(cmd, capture_output=True, text=True)
        dt = time.time() - t0
    res = {10: 'SAT', 20: 'UNSAT'}.get(p.returncode, 'UNKNOWN')
    model = {}
    if res == 'SAT':
        for l in p.stdout.split('\n'):
            if l.startswith('v '):
                for lit in map(int, l[2:].split()):
                    if lit: model[abs(lit)] = lit > 0
    tail = [l for l in p.stdout.split('\n') if l.startswith('s ') or 'total process time' in l
            or 'maximum resident' in l]
    return res, model, dt, tail

# ---------------------------------------------------------------- checks


def cost_of(plan, goals, cost):
    n = len(goals)
    if cost == 'loss':
        return sum(1 for t in range(1, len(plan)) for i in range(n)
                   if not (plan[t - 1][i] == goals[i] and plan[t][i] == goals[i]))
    return sum(max([t for t in range(len(plan)) if plan[t][i] != goals[i]], default=-1) + 1 for i in range(n))


def own_check(g, starts, goals, plan):
    if plan[0] != list(starts) or plan[-1] != list(goals): return 'bad start or end'
    for t in range(1, len(plan)):
        a, b = plan[t - 1], plan[t]
        if len(set(b)) < len(b): return f'vertex conflict at t={t}'
        for i in range(len(a)):
            if a[i] != b[i] and b[i] not in g.nb[a[i]]: return f'agent {i} jumps at t={t}'
            for j in range(len(a)):
                if i != j and a[i] == b[j] and a[j] == b[i] and a[i] != b[i]: return f'swap at t={t}'
    return ''


def importable(mod):
    try:
        __import__(mod)
        return True
    except ImportError:
        return False


def project_check(map_path, g, starts, goals, plan):
    """The project's validator (Python bindings) on the plan: (error, sum_of_costs) or None."""
    try:
        import rtlacam
    except ImportError:
        return None
    pg = rtlacam.load_map(map_path)
    conv = lambda cfg: [pg.at(*g.cells[v]) for v in cfg]
    err = rtlacam.validate_plan(pg, conv(starts), conv(goals), [conv(c) for c in plan])
    v = rtlacam.Validator(pg, conv(starts), conv(goals))
    for c in plan[1:]: v.step(conv(c))
    return err, v.sum_of_costs


def write_plan(path, map_path, g, starts, goals, plan, soc, lb):
    xy = lambda cfg: ','.join(f'({g.cells[v][0]},{g.cells[v][1]})' for v in cfg)
    with open(path, 'w') as f:  # planner/plan_io.hpp's format
        f.write(f'agents={len(starts)}\nmap_file={os.path.basename(map_path)}\nsolver=sat-cadical\nsolved=1\n'
                f'soc={soc}\nsoc_lb={lb}\nmakespan={len(plan) - 1}\ncomp_time=0\n'
                f'starts={xy(starts)},\ngoals={xy(goals)},\nsolution=\n')
        for t, c in enumerate(plan): f.write(f'{t}:{xy(c)},\n')


def brute(g, starts, goals, cost):
    """Exact optimum by Dijkstra over joint states (loss: configurations; soc: plus the set of
    agents that have stopped for good on their goals)."""
    n = len(starts)
    S0, G = tuple(starts), tuple(goals)
    if cost == 'soc':  # agents starting on their goals may have stopped already
        home = [i for i in range(n) if S0[i] == G[i]]
        sources = [(S0, sum(1 << i for i in sub)) for r in range(len(home) + 1) for sub in itertools.combinations(home, r)]
    else:
        sources = [(S0,)]
    best = {s: 0 for s in sources}
    pq = [(0, s) for s in sources]
    while pq:
        c, st = heapq.heappop(pq)
        if best[st] < c: continue
        cfg = st[0]
        if cfg == G and (cost == 'loss' or st[1] == (1 << n) - 1): return c
        done = st[1] if cost == 'soc' else 0
        opts = [[v] if done >> i & 1 else g.nb[v] + [v] for i, v in enumerate(cfg)]
        for nx in itertools.product(*opts):
            if len(set(nx)) < n: continue
            if any(cfg[i] != nx[i] and cfg[i] == nx[j] and cfg[j] == nx[i] for i in range(n) for j in range(n) if i != j):
                continue
            if cost == 'loss':
                nc, ns = c + sum(1 for i in range(n) if not (cfg[i] == G[i] and nx[i] == G[i])), (nx,)
                cands = [(nc, ns)]
            else:  # every not-yet-stopped agent pays; agents on their goal may stop now
                nc = c + sum(1 for i in range(n) if not done >> i & 1)
                free = [i for i in range(n) if not done >> i & 1 and nx[i] == G[i]]
                cands = [(nc, (nx, done | sum(1 << i for i in sub)))
                         for r in range(len(free) + 1) for sub in itertools.combinations(free, r)]
            for nc, ns in cands:
                if nc < best.get(ns, 1 << 60):
                    best[ns] = nc
                    heapq.heappush(pq, (nc, ns))
    return None


def sat_optimum(g, starts, goals, cost, dmax=40, pairs=True):
    sur = pair_surplus(g, starts, goals) if pairs else {}
    for D in range(dmax + 1):
        enc = encode(g, starts, goals, D, cost, sur)
        if enc is None: return None, None
        if enc == 'UNSAT': continue
        cnf, x, T, lb = enc
        res, model, _, _ = solve(cnf, None)
        if res == 'SAT':
            return lb + D, decode(g, starts, goals, x, T, model)
    return None, None


def self_check(trials, seed):
    rng = random.Random(seed)
    pv = project_check is not None and importable('rtlacam')
    print('project validator (rtlacam bindings):', 'on' if pv else 'not importable (PYTHONPATH=build/python)')
    done = 0
    while done < trials:
        w, h = rng.choice([(3, 3), (4, 3), (4, 4), (5, 3), (2, 5)])
        rows = [''.join('@' if rng.random() < 0.2 else '.' for _ in range(w)) for _ in range(h)]
        g = Grid(rows)
        n = rng.choice([2, 3, 3, 4])
        if len(g.cells) < n + 1: continue
        comp = g.bfs(0)
        if any(c is None for c in comp): continue  # connected maps only: solvable is then decided by brute
        starts, goals = rng.sample(range(len(g.cells)), n), rng.sample(range(len(g.cells)), n)
        for cost in ('loss', 'soc'):
            opt = brute(g, starts, goals, cost)
            if opt is None: break
            for pairs in (False, True):
                sat, plan = sat_optimum(g, starts, goals, cost, opt - sum(g.bfs(t)[s] for s, t in zip(starts, goals)) + 1,
                                        pairs)
                ok = sat == opt and not own_check(g, starts, goals, plan) and cost_of(plan, goals, cost) == opt
                if ok and pv:  # and the project's validator agrees: valid, the same loss
                    with tempfile.NamedTemporaryFile('w', suffix='.map') as f:
                        f.write(f'type octile\nheight {h}\nwidth {w}\nmap\n' + '\n'.join(rows) + '\n')
                        f.flush()
                        err, loss = project_check(f.name, g, starts, goals, plan)
                    ok = not err and loss == cost_of(plan, goals, 'loss')
                print(f'{"ok  " if ok else "FAIL"} {rows} starts {starts} goals {goals} cost {cost} pair bounds '
                      f'{"on " if pairs else "off"}: exhaustive {opt}, sat {sat}', flush=True)
                if not ok: return False
        else:
            done += 1
    print(f'self-check passed: {trials} random instances x 2 costs x pair bounds off/on, SAT optimum == exhaustive optimum,'
          ' decoded plans valid and of that cost' + (' (project validator: valid, same loss)' if pv else ''))
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('map', nargs='?')
    ap.add_argument('scen', nargs='?')
    ap.add_argument('-N', '--agents', type=int, default=16)
    ap.add_argument('--cost', choices=['loss', 'soc'], default='loss')
    ap.add_argument('--target', type=int, help='decide: a plan of cost <= TARGET?')
    ap.add_argument('--minimise', action='store_true', help='binary search in [--lo, --hi] for the optimum')
    ap.add_argument('--lo', type=int, help='a proven lower bound (default LB)')
    ap.add_argument('--hi', type=int, help='a known feasible cost (default: raise until SAT)')
    ap.add_argument('--timeout-s', type=float, default=1800, help='per SAT call')
    ap.add_argument('--plan-out', help='write the best plan found (plan_io format)')
    ap.add_argument('--keep-cnf', help='keep the last CNF at this path')
    ap.add_argument('--no-pairs', action='store_true', help='no pair-surplus bounds (slower proofs)')
    ap.add_argument('--self-check', action='store_true')
    ap.add_argument('--trials', type=int, default=30)
    ap.add_argument('--seed', type=int, default=0)
    a = ap.parse_args()
    if a.self_check:
        sys.exit(0 if self_check(a.trials, a.seed) else 1)
    if not a.map or not a.scen: ap.error('MAP and SCEN are required (or --self-check)')
    g, starts, goals = load(a.map, a.scen, a.agents)
    lb = sum(g.bfs(t)[s] for s, t in zip(starts, goals))
    print(f'{a.map} {a.scen}: {len(g.cells)} cells, {len(starts)} agents, LB {lb}, cost {a.cost}', flush=True)
    t0 = time.time()
    sur = {} if a.no_pairs else pair_surplus(g, starts, goals)
    M = matching_bounds(len(starts), sur)
    print(f'pair surpluses ({time.time() - t0:.1f} s): {sum(sur.values())} over {len(sur)} pairs, matching bound '
          f'LB + {M[-1]} = {lb + M[-1]}; own slack of agent i = D - {M[:-1]}', flush=True)

    def run(target):
        t0 = time.time()
        enc = encode(g, starts, goals, target - lb, a.cost, sur)
        if enc == 'UNSAT':
            print(f'cost <= {target}: UNSAT by the pair matching bound alone', flush=True)
            return 'UNSAT', None
        cnf, x, T, _ = enc
        enc_s = time.time() - t0
        res, model, dt, tail = solve(cnf, a.timeout_s, a.keep_cnf)
        print(f'cost <= {target} (D {target - lb}, horizon {T}): {res} -- {cnf.n} vars, {len(cnf.cl)} clauses, '
              f'encode {enc_s:.1f} s, cadical {dt:.1f} s | ' + ' | '.join(l.strip() for l in tail), flush=True)
        if res != 'SAT': return res, None
        plan = decode(g, starts, goals, x, T, model)
        c, err = cost_of(plan, goals, a.cost), own_check(g, starts, goals, plan)
        pc = project_check(a.map, g, starts, goals, plan)
        print(f'  decoded plan: makespan {len(plan) - 1}, {a.cost} {c}, loss {cost_of(plan, goals, "loss")}, '
              f'soc {cost_of(plan, goals, "soc")}; own check: {err or "valid"}; project validator: '
              + ('not importable (PYTHONPATH=build/python)' if pc is None else f'{pc[0] or "valid"}, sum_of_costs {pc[1]}'),
              flush=True)
        if err or c > target or (pc is not None and pc[0]): sys.exit('decoded plan is wrong: encoding bug')
        if a.plan_out: write_plan(a.plan_out, a.map, g, starts, goals, plan, cost_of(plan, goals, 'loss'), lb)
        return res, c

    if a.target is not None and not a.minimise:
        res, _ = run(a.target)
        sys.exit({'SAT': 0, 'UNSAT': 0}.get(res, 2))
    lo = (a.lo if a.lo is not None else lb) - 1  # lo: cost proven infeasible (or below LB)
    hi = a.hi
    if hi is not None:  # verify the known solution's cost (and keep its plan)
        res, c = run(hi)
        if res != 'SAT': sys.exit(f'--hi {hi}: {res}')
        hi = c
    else:
        t = lo + 1
        while True:
            res, c = run(t)
            if res == 'SAT': hi = c; break
            if res != 'SAT' and res != 'UNSAT': sys.exit(f'unknown at {t}: give more time')
            lo, t = t, t + max(1, (t - lb) // 4 + 1)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        res, c = run(mid)
        if res == 'SAT': hi = c
        elif res == 'UNSAT': lo = mid
        else: sys.exit(f'optimum in [{lo + 1}, {hi}]: unknown at {mid} (timeout)')
    print(f'OPTIMUM ({a.cost}) = {hi}: {hi} feasible, {hi - 1} proven infeasible; ratio to LB {hi / lb:.3f}')


if __name__ == '__main__':
    main()
