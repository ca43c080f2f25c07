#!/usr/bin/env python3
"""Lifelong throughput with each warehouse traffic rule on and off (issue 24; controller/rules.hpp).

For each warehouse, four runs of rtlacam-sumo in the same invocation, identical but for the
rules: off (no closure, no zone, no lane watch), closure (a picking aisle closed over
[20 %, 50 %) of the run, as a YAML event), one-way closure (only its first direction's lane
closed over the same window: the cells stay open the other way), zone (a cross aisle as a
one-at-a-time zone), both (closure and zone). --executor runs them all under lockstep, adg or
adg-follow (default: the config's).
Then one-way versus two-way aisles on the large layout: config/large_warehouse_lifelong.yaml
against config/large_oneway_lifelong.yaml (the same layout, stations, starts and tasks, its
picking aisles one-way in alternate directions; sumo_scenarios/make_warehouse.py), rules off.
The planner has a fixed number of expansions per SUMO step (deterministic decisions, so the
rules alone make the difference). Prints errands per tick, the ratio to "off", K (the
longest stall of a busy AGV's errand: ticks without getting closer to it, max / p99;
tasks/errand_stalls.hpp), the longest errand from assignment to completion, and the rule counters; every run must end clean (0 collisions, 0 violations,
0 jumps / re-syncs; the script says so).

  scripts/bench_rules.py [--build build] [--ticks 1000] [--large-ticks 500] [--expansions 50]
                         [--skip-large] [--skip-one-way] [--skip-small] [--queues]
                         [--station-closure] [--executor lockstep|adg|adg-follow]
                         [--solver rtlacam|pibt|pibt-rot|epibt|wppl|...] [--planner KEY=VALUE ...]
                         [--urgency [--urgency-configs CONFIG...]] [--shipped-k CONFIG...]
                         [--long-k CONFIG... [--seeds 1,2,3,4] [--large-ticks-list 4000,16000] [--jobs 2]]
                         [--admission [--admission-configs CONFIG...] [--seeds 1,2]]
                         [--pocket-clear N [--clear-configs CONFIG...] [--seeds 1,2] [--off-build BUILD]]
                         [--task-variants JSON... [--clear-configs CONFIG...] [--seeds 1,2]
                          [--large-ticks-list 1000,2000] [--jobs 2]]
                         [--queue-variants JSON... [--clear-configs CONFIG...] [--seeds 1,2]
                          [--large-ticks-list 1000,2000] [--jobs 2]]
                         [--stall-rules [--stall-configs CONFIG...] [--seeds 1,2] [--swap-after 30]
                          [--head-after 60] [--load-cost 0] [--pocket-cost 100] [--drop-hints [--against-rules]]]

--station-closure: instead, per warehouse, a pick-up station's stub closed over [20 %, 50 %)
(its errands cut off) with rules.reassign on (the errand goes back to the pool) and off (its
AGV waits), against no closure; prints the tasks handed back.
--solver: every run with this planner.solver (default: the config's, rtlacam); a rotation
solver (pibt-rot, epibt, wppl) gets the controller's rotation defaults (guidance arrows for
pibt-rot and epibt) and restarts on the rules' graph from the AGVs' cells and headings.
--urgency: instead, the task layer's priority hints (tasks/urgency.hpp) on and off, rules
off, on each of --urgency-configs (default: the large two-way and one-way warehouses and the
small one), same ticks, expansions and seeds: errands per tick on / off and K both ways.
--long-k CONFIG... [--seeds 1,2,3,4] [--large-ticks-list 4000,16000] [--jobs 2]: instead, each config
as shipped, with its own planner budget (not --expansions) and endless tasks, per fleet seed and
tick count: errands per tick and K per seed (does the longest stall grow with the run?).
--shipped-k CONFIG...: instead, each config as shipped (its rules, queues, hints), with the
fixed expansions and --ticks (small configs) / --large-ticks: K of the shipped examples.
--admission [--admission-configs CONFIG...] [--seeds 1,2]: instead, station admission
(tasks/station_queues.hpp: queues {capacity 1, length 8}, pool admission, oldest request
first, planner.keep_priorities) on against off (no queues), per config (default: the four
large lifelong examples) and fleet seed, same ticks (--large-ticks) and expansions:
errands per tick on / off and K both ways.
--pocket-clear N [--clear-configs CONFIG...] [--seeds 1,2] [--off-build BUILD]: instead, pocket
clearing (tasks.queues.clear_after N, tasks/station_queues.hpp) on against off (the config
without clear_after), per config with station queues (default: the large queues and parking
examples) and fleet seed, same ticks (--large-ticks) and expansions; the off side runs
--off-build when given (e.g. main's build: also without this build's other changes).
--stall-rules: instead, the task layer's stall rules (tasks/urgency.hpp: stall handover
swap_after, head hints head_after with agents leaving a dead-end pocket first, station load
load_cost, foreign-pocket cost pocket_cost; with --drop-hints also drop_hints, with --mouth-cost N
the stub-mouth routing cost mouth_cost, with --sticky sticky stalls) on against all off
(--against-rules: against the same rules without the newest ones given: mouth_cost and sticky
when either is given, else drop_hints), per config (default: the large two-way and one-way warehouses)
and fleet seed, same ticks (--large-ticks) and expansions: errands per tick on / off and K.
--queues: every run with station queues {capacity 1, length 8} and planner.keep_priorities
(the setting that keeps the large warehouse from collapsing: docs/twin_bench.md).
"""
import argparse
import copy
import json
import os
import subprocess
import sys
import tempfile
import time

import yaml  # PyYAML

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The stub of one pick-up station per warehouse (--station-closure).
STATION_STUB = {"small": ["c1r0_pick1", "pick1_c1r0"], "large": ["c0r0_pick0", "pick0_c0r0"]}

# name, config, ticks option, closure edges, candidate zone edges (the first whose cells hold
# no two random starts is used: a zone may hold one AGV only, from the start on)
WAREHOUSES = [
    ("small (16 AGVs)", "config/small_warehouse_lifelong.yaml", "ticks",
     ["c1r0_c1r1", "c1r1_c1r0"], [["c1r1_c2r1"], ["c2r1_c3r1"], ["c0r1_c1r1"]]),
    ("large (200 AGVs)", "config/large_warehouse_lifelong.yaml", "large_ticks",
     ["c5r0_c5r1", "c5r1_c5r0"],
     [["c5r1_c6r1"], ["c6r1_c7r1"], ["c4r1_c5r1"], ["c7r1_c8r1"], ["c3r1_c4r1"], ["c8r1_c9r1"], ["c2r1_c3r1"]]),
]


QUEUES = False
EXECUTOR = None  # --executor: every run under it (None: the config's)
SOLVER = None  # --solver: every run with it (None: the config's)
PLANNER = {}  # --planner KEY=VALUE: planner keys set in every run


def k_cols(m):
    """K = stall ticks max / p99, and errand ticks (assignment to completion) max."""
    l = m["lifelong"]
    return f"{l['stallTicks']['max']} / {l['stallTicks']['p99']} | {l['errandTicks']['max']}"


def run_clean(m):
    """0 violations, 0 jumps / re-syncs, 0 collisions, no error."""
    return m["violations"] == 0 and m["teleports_or_jumps"] == 0 and m.get("collisions", 0) == 0 and not m["error"]


_CONFIGS = {}


def shipped(base):
    """The config as it was when this invocation first read it (a copy): editing a config while
    a long bench runs must not change its "as is" runs half way."""
    if base not in _CONFIGS:
        with open(os.path.join(ROOT, base)) as f:
            _CONFIGS[base] = yaml.safe_load(f)
    return copy.deepcopy(_CONFIGS[base])


def run(build, base, out, ticks, expansions, rules, tasks_extra=None, sections=None):
    cfg = shipped(base)
    here = os.path.dirname(os.path.join(ROOT, base))
    for k in ("net", "additional"):
        if k in cfg["sumo"]:
            cfg["sumo"][k] = os.path.normpath(os.path.join(here, cfg["sumo"][k]))
    cfg["sumo"]["outputs"] = {"fcd": False, "tripinfo": False, "summary": False, "collision": True}
    if expansions is not None:  # None: the config's own budget (budget_ms or expansions)
        cfg["planner"]["budget_ms"] = 0
        cfg["planner"]["expansions"] = expansions
    cfg["run"]["max_ticks"] = ticks
    cfg["run"]["progress_s"] = 0
    if EXECUTOR:
        cfg["run"]["executor"] = EXECUTOR
    if SOLVER:
        cfg["planner"]["solver"] = SOLVER
    cfg["planner"].update(PLANNER)
    cfg["output"] = {"dir": out, "congestion": False}
    if rules is not None:
        cfg["rules"] = rules
    cfg["tasks"].update(tasks_extra or {})
    for section, values in (sections or {}).items():
        cfg[section].update(values)
    if QUEUES:
        cfg["tasks"]["queues"] = {"capacity": 1, "length": 8}
        cfg["planner"]["keep_priorities"] = True
    path = out + ".yaml"
    with open(path, "w") as f:
        yaml.safe_dump(cfg, f)
    p = subprocess.run([os.path.join(build, "apps", "rtlacam-sumo"), path], capture_output=True, text=True)
    if p.returncode == 2:
        return None, p.stderr.strip()
    m = json.load(open(os.path.join(out, "metrics.json")))
    return m, p.stderr


def station_closure(a, build, tmp):
    clean = True
    print("| warehouse | station closure | ticks | errands/tick | vs no closure | K (stall max / p99) | errand ticks max | tasks handed back | violations | jumps+resyncs |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, base, tick_opt, _, _ in WAREHOUSES:
        key = name.split()[0]
        if (a.skip_large and key == "large") or (a.skip_small and key == "small"):
            continue
        ticks = getattr(a, tick_opt)
        closure = [{"edges": STATION_STUB[key], "begin": round(0.2 * ticks), "end": round(0.5 * ticks)}]
        base_rate = None
        for label, extra in [("none", {}), ("reassign", {"closures": closure, "reassign": True}),
                             ("wait (reassign off)", {"closures": closure, "reassign": False})]:
            rules = {"sumo": False, "watch_lanes": False}
            rules.update(extra)
            out = os.path.join(tmp, key + "_station_" + label.split()[0])
            m, err = run(build, base, out, ticks, a.expansions, rules)
            if m is None:
                print(f"# {name} {label}: {err}", file=sys.stderr)
                return 1
            rate = m["lifelong"]["errandThroughput"]
            base_rate = rate if base_rate is None else base_rate
            jr = m["teleports_or_jumps"]
            clean = clean and run_clean(m)
            print(f"| {name} | {label} | {m['ticks']} | {rate:.3f} | {rate / base_rate if base_rate else 0:.2f} | "
                  f"{k_cols(m)} | {m['lifelong'].get('reassignedForClosure', 0)} | "
                  f"{m['violations']} | {jr} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


def on_off(build, base, out, ticks, expansions, variants):
    """The same config run "on" and "off": variants = {label: (rules, tasks_extra, sections)}.
    Returns ({label: metrics}, clean), or (None, error) when a run was refused."""
    res, clean = {}, True
    for label, (rules, tasks_extra, sections) in variants.items():
        m, err = run(build, base, f"{out}_{label}", ticks, expansions, rules, tasks_extra, sections)
        if m is None:
            return None, f"{label}: {err}"
        clean = clean and run_clean(m)
        res[label] = m
    return res, clean


def on_off_cols(res):
    """errands/tick on | off | on / off | K on | K off (stall ticks max / p99)."""
    on, off = res["on"]["lifelong"], res["off"]["lifelong"]
    ro, rf = on["errandThroughput"], off["errandThroughput"]
    return (f"{ro:.3f} | {rf:.3f} | {ro / rf if rf else 0:.2f} | "
            f"{on['stallTicks']['max']} / {on['stallTicks']['p99']} | {off['stallTicks']['max']} / {off['stallTicks']['p99']}")


def urgency(a, build, tmp):
    """Priority hints on against off, per config (same ticks, seeds, expansions)."""
    clean = True
    print("| config | ticks | errands/tick on | off | on / off | K on (stall max / p99) | K off | errands done on / off |")
    print("|---|---|---|---|---|---|---|---|")
    rules = {"sumo": False, "watch_lanes": False}
    for base in a.urgency_configs:
        ticks = a.ticks if "small" in base else a.large_ticks
        out = os.path.join(tmp, os.path.basename(base).split(".")[0] + "_urgency")
        res, ok = on_off(build, base, out, ticks, a.expansions,
                         {"on": (rules, {"urgency": {"stalls": True, "battery": True}}, None),
                          "off": (rules, {"urgency": {"stalls": False, "battery": False}}, None)})
        if res is None:
            print(f"# {base} {ok}", file=sys.stderr)
            return 1
        clean = clean and ok
        print(f"| {base} | {res['on']['ticks']} | {on_off_cols(res)} | "
              f"{res['on']['lifelong']['numErrandFinished']} / {res['off']['lifelong']['numErrandFinished']} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


def admission(a, build, tmp):
    """Station admission on against off, per config and fleet seed (same ticks, expansions)."""
    clean = True
    print("| config | seed | ticks | errands/tick on | off | on / off | K on (stall max / p99) | K off | busy-errand ticks max on / off |")
    print("|---|---|---|---|---|---|---|---|---|")
    seeds = [int(x) for x in a.seeds.split(",") if x]
    for base in a.admission_configs:
        ticks = a.ticks if "small" in base else a.large_ticks
        for seed in seeds:
            out = os.path.join(tmp, f"{os.path.basename(base).split('.')[0]}_{seed}_admission")
            res, ok = on_off(build, base, out, ticks, a.expansions,
                             {"on": (None, {"queues": {"capacity": 1, "length": 8}},
                                     {"fleet": {"seed": seed}, "planner": {"keep_priorities": True}}),
                              "off": (None, {"queues": {"capacity": 0}}, {"fleet": {"seed": seed}})})
            if res is None:
                print(f"# {base} {ok}", file=sys.stderr)
                return 1
            clean = clean and ok
            print(f"| {base} | {seed} | {res['on']['ticks']} | {on_off_cols(res)} | "
                  f"{res['on']['lifelong']['errandTicks']['max']} / {res['off']['lifelong']['errandTicks']['max']} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


def shipped_k(a, build, tmp):
    """K of each shipped lifelong example as it is (its rules, queues and hints), scaled ticks."""
    clean = True
    print("| config | ticks | errands/tick | K (stall max / p99) | errand ticks max | errands | violations | jumps+resyncs |")
    print("|---|---|---|---|---|---|---|---|")
    for base in a.shipped_k:
        ticks = a.ticks if "small" in base else a.large_ticks
        out = os.path.join(tmp, os.path.basename(base).split(".")[0] + "_shipped")
        m, err = run(build, base, out, ticks, a.expansions, None)
        if m is None:
            print(f"# {base}: {err}", file=sys.stderr)
            return 1
        clean = clean and run_clean(m)
        l = m["lifelong"]
        print(f"| {base} | {m['ticks']} | {l['errandThroughput']:.3f} | {k_cols(m)} | {l['numErrandFinished']} | "
              f"{m['violations']} | {m['teleports_or_jumps']} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


def long_k(a, build, tmp):
    """K over long runs: each config as shipped (its own planner budget, rules, queues, hints)
    with endless tasks (tasks.random.count 10^6), per fleet seed and tick count: does the longest
    stall grow with the run?"""
    from concurrent.futures import ThreadPoolExecutor
    ticks_list = [int(t) for t in a.large_ticks_list.split(",")]
    seeds = [int(s) for s in a.seeds.split(",")]
    jobs = [(base, t, seed) for base in a.long_k for t in ticks_list for seed in seeds]

    def one(job):
        base, t, seed = job
        out = os.path.join(tmp, f"{os.path.basename(base).split('.')[0]}_{t}_s{seed}")
        cfg = shipped(base)
        endless = {"random": dict(cfg["tasks"]["random"], count=10 ** 6)} if "random" in cfg["tasks"] else {}
        return job, run(build, base, out, t, None, None, endless, {"fleet": {"seed": seed}})

    with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        results = dict(ex.map(one, jobs))
    clean = True
    print(f"# fleet seeds {a.seeds}; each config's own planner budget; tasks.random.count 10^6")
    print("| config | ticks | errands/tick (mean) | K per seed (stall max) | stall p99 max | errand ticks max |")
    print("|---|---|---|---|---|---|")
    for base in a.long_k:
        for t in ticks_list:
            ms = []
            for seed in seeds:
                m, err = results[(base, t, seed)]
                if m is None:
                    print(f"# {base} seed {seed}: {err}", file=sys.stderr)
                    continue
                clean = clean and run_clean(m)
                ms.append(m)
            if not ms:
                continue
            ls = [m["lifelong"] for m in ms]
            print(f"| {base} | {t} | {sum(l['errandThroughput'] for l in ls) / len(ls):.3f} | "
                  f"{' / '.join(str(l['stallTicks']['max']) for l in ls)} | {max(l['stallTicks']['p99'] for l in ls)} | "
                  f"{max(l['errandTicks']['max'] for l in ls)} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


def stall_rules(a, build, tmp):
    """Stall handover, head hints and station load (tasks/urgency.hpp: swap_after, head_after,
    load_cost, pocket_cost) on against off, per config and fleet seed (same ticks, expansions)."""
    clean = True
    on = {"swap_after": a.swap_after, "head_after": a.head_after, "load_cost": a.load_cost, "pocket_cost": a.pocket_cost}
    off = {"swap_after": 0, "head_after": 0, "load_cost": 0, "pocket_cost": 0}
    if a.drop_hints:
        on["drop_hints"] = True
    if a.mouth_cost:
        on["mouth_cost"] = a.mouth_cost
    if a.sticky:
        on["sticky"] = True
    if a.against_rules:  # off = the same rules without the newest given: their own effect
        if a.mouth_cost or a.sticky:
            off = {k: v for k, v in on.items() if k not in ("mouth_cost", "sticky")}
        else:
            off = dict(on, drop_hints=False)
    print(f"# on: tasks.urgency {on}; off: {off}")
    print("| config | seed | ticks | errands/tick on | off | on / off | K on (stall max / p99) | K off | errand ticks max on / off |")
    print("|---|---|---|---|---|---|---|---|---|")
    seeds = [int(x) for x in a.seeds.split(",") if x]
    for base in a.stall_configs:
        ticks = a.ticks if "small" in base else a.large_ticks
        for seed in seeds:
            out = os.path.join(tmp, f"{os.path.basename(base).split('.')[0]}_{seed}_stall")
            res, ok = on_off(build, base, out, ticks, a.expansions,
                             {"on": (None, {"urgency": dict(on)}, {"fleet": {"seed": seed}}),
                              "off": (None, {"urgency": dict(off)}, {"fleet": {"seed": seed}})})
            if res is None:
                print(f"# {base} {ok}", file=sys.stderr)
                return 1
            clean = clean and ok
            print(f"| {base} | {seed} | {res['on']['ticks']} | {on_off_cols(res)} | "
                  f"{res['on']['lifelong']['errandTicks']['max']} / {res['off']['lifelong']['errandTicks']['max']} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


def pocket_clear(a, build, tmp):
    """Pocket clearing (tasks.queues.clear_after, tasks/station_queues.hpp) on against the config
    as it is, per config with station queues and fleet seed (same ticks, expansions). With
    --off-build the off side runs that build (e.g. main's: also without this build's other changes)."""
    clean = True
    off_build = os.path.abspath(a.off_build) if a.off_build else build
    off_what = f"the same clear_after {a.pocket_clear}" if a.off_as_is else "the config without clear_after"
    off_what += ", without in_line"
    on_what = f"tasks.queues.clear_after {a.pocket_clear}" + (", in_line true" if a.in_line else "")
    print(f"# on: {on_what} ({build}); off: {off_what} ({off_build})")
    print("| config | seed | ticks | errands/tick on | off | on / off | K on (stall max / p99) | K off | errand ticks max on / off | clearings on |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    seeds = [int(x) for x in a.seeds.split(",") if x]
    for base in a.clear_configs:
        ticks = a.ticks if "small" in base else a.large_ticks
        cfg = shipped(base)
        queues = dict(cfg["tasks"].get("queues") or {}, clear_after=a.pocket_clear)
        plain = {k: v for k, v in queues.items() if k != "clear_after"}  # off: 0 (and readable by older builds)
        for seed in seeds:
            out = os.path.join(tmp, f"{os.path.basename(base).split('.')[0]}_{seed}_clear")
            res = {}
            off_queues = dict(queues if a.off_as_is else plain)
            off_queues.pop("in_line", None)  # off: without in_line (and readable by older builds)
            if a.in_line:
                queues["in_line"] = True
            for label, b, extra in (("on", build, {"queues": queues}), ("off", off_build, {"queues": off_queues})):
                m, err = run(b, base, f"{out}_{label}", ticks, a.expansions, None, extra, {"fleet": {"seed": seed}})
                if m is None:
                    print(f"# {base} {label}: {err}", file=sys.stderr)
                    return 1
                clean = clean and run_clean(m)
                res[label] = m
            print(f"| {base} | {seed} | {res['on']['ticks']} | {on_off_cols(res)} | "
                  f"{res['on']['lifelong']['errandTicks']['max']} / {res['off']['lifelong']['errandTicks']['max']} | "
                  f"{res['on']['lifelong'].get('queues', {}).get('clearings', '-')} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


def queue_variants(a, build, tmp):
    """tasks.queues overrides (JSON mappings, --queue-variants) against the config as is, per
    config (--clear-configs), fleet seed (--seeds) and tick count (--large-ticks-list), on
    one build: the first row of each (config, seed, ticks) is the config as is, the others print
    their ratio to it. --jobs runs that many rtlacam-sumo at once (decisions do not depend on
    timing: the planner has a fixed number of expansions per step)."""
    return variant_runs(a, build, tmp, [(v, {"queues": json.loads(v)}) for v in a.queue_variants], summary=False)


def deep_merge(d, over):
    """d with `over` merged in, mappings key by key (a copy; neither argument changes)."""
    out = dict(d or {})
    for k, v in over.items():
        out[k] = deep_merge(out.get(k), v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out


def task_variants(a, build, tmp):
    """tasks.* overrides (JSON mappings merged key by key into the config's tasks section,
    --task-variants, e.g. '{"urgency": {"escalate_after": 150}}') against the config as is, per
    config (--clear-configs), tick count (--large-ticks-list) and fleet seed (--seeds), on one
    build: the same table as --queue-variants, then per variant the mean of its per-run ratios
    and its K max over the runs."""
    return variant_runs(a, build, tmp, [(v, json.loads(v)) for v in a.task_variants], summary=True)


def variant_runs(a, build, tmp, overrides, summary):
    """The runs of --queue-variants / --task-variants: each (label, tasks override) merged key by
    key into each config's tasks section, after the config as is; queue_rows' table, then with
    `summary` per variant the mean ratio and K max."""
    from concurrent.futures import ThreadPoolExecutor
    variants = [("as is", {})] + overrides
    seeds = [int(x) for x in a.seeds.split(",") if x]
    ticks_list = [int(x) for x in str(a.large_ticks_list).split(",") if x]
    jobs = []
    for base in a.clear_configs:
        cfg = shipped(base)
        for ticks in ticks_list:
            for seed in seeds:
                for k, (label, over) in enumerate(variants):
                    out = os.path.join(tmp, f"{os.path.basename(base).split('.')[0]}_{ticks}_{seed}_v{k}")
                    jobs.append((base, ticks, seed, label, out, deep_merge(cfg["tasks"], over)))
    t0 = time.time()
    with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        futs = [ex.submit(run, build, base, out, ticks, a.expansions, None, t, {"fleet": {"seed": seed}})
                for base, ticks, seed, label, out, t in jobs]
        rc = queue_rows(jobs, futs, t0, a, build)
        if not summary:
            return rc
        per = {}
        for (base, ticks, seed, label, out, t), f in zip(jobs, futs):
            m = f.result()[0]
            if m is None:
                continue
            l = m["lifelong"]
            if label == "as is":
                base_rate = l["errandThroughput"]
            s = per.setdefault((base, ticks, label), [[], []])
            s[0].append(l["errandThroughput"] / base_rate if base_rate else 0)
            s[1].append(l["stallTicks"]["max"])
        for (base, ticks, label), (ratios, ks) in per.items():
            print(f"# {base} {ticks} ticks, {label}: mean ratio {sum(ratios) / len(ratios):.3f} "
                  f"(min {min(ratios):.2f}), K max {max(ks)} (per seed {' / '.join(map(str, ks))})")
        return rc


def queue_rows(jobs, futs, t0, a, build):
    """queue_variants' table, a row as each run ends (in order)."""
    print(f"# build {build}, {a.jobs} runs at once, {a.expansions} expansions per step", flush=True)
    print("| config | ticks | seed | variant | errands/tick | / as is | K (stall max / p99) | errand ticks max | clearings | longest clearing | clean |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    clean, base_rate = True, None
    for (base, ticks, seed, label, out, q), f in zip(jobs, futs):
        m, err = f.result()
        if m is None:  # the config refused this seed (e.g. two starts in a zone): skipped, said once
            if label == "as is":
                print(f"# {base} seed {seed} skipped: {err.splitlines()[-1] if err else 'refused'}", flush=True)
            continue
        ok = run_clean(m)
        clean = clean and ok
        l = m["lifelong"]
        rate = l["errandThroughput"]
        if label == "as is":
            base_rate = rate
        print(f"| {base} | {m['ticks']} | {seed} | {label} | {rate:.3f} | {rate / base_rate if base_rate else 0:.2f} | "
              f"{l['stallTicks']['max']} / {l['stallTicks']['p99']} | {l['errandTicks']['max']} | "
              f"{l.get('queues', {}).get('clearings', '-')} | {l.get('queues', {}).get('longestClearing', '-')} | "
              f"{'yes' if ok else 'NO'} |", flush=True)
    print(f"# {len(jobs)} runs in {time.time() - t0:.0f} s")
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--ticks", type=int, default=1000)
    ap.add_argument("--large-ticks", type=int, default=1000)
    ap.add_argument("--expansions", type=int, default=50)
    ap.add_argument("--skip-large", action="store_true")
    ap.add_argument("--skip-one-way", action="store_true")
    ap.add_argument("--skip-small", action="store_true")
    ap.add_argument("--queues", action="store_true")
    ap.add_argument("--station-closure", action="store_true")
    ap.add_argument("--executor", choices=["lockstep", "adg", "adg-follow"])
    ap.add_argument("--solver")
    ap.add_argument("--urgency", action="store_true")
    ap.add_argument("--shipped-k", nargs="+", metavar="CONFIG")
    ap.add_argument("--long-k", nargs="+", metavar="CONFIG",
                    help="K over long runs: each config with its own planner budget and endless tasks, per fleet seed "
                         "(--seeds) and tick count (--large-ticks-list), --jobs at once")
    ap.add_argument("--admission", action="store_true")
    ap.add_argument("--admission-configs", nargs="+",
                    default=["config/large_warehouse_lifelong.yaml", "config/large_oneway_lifelong.yaml",
                             "config/large_warehouse_queues.yaml", "config/large_warehouse_parking.yaml"])
    ap.add_argument("--seeds", default="1,2", help="--admission, --stall-rules: fleet seeds")
    ap.add_argument("--stall-rules", action="store_true")
    ap.add_argument("--pocket-clear", type=int, default=0, metavar="N",
                    help="tasks.queues.clear_after N against the config as is (--clear-configs, --seeds, --off-build)")
    ap.add_argument("--clear-configs", nargs="+",
                    default=["config/large_warehouse_queues.yaml", "config/large_warehouse_parking.yaml"])
    ap.add_argument("--in-line", action="store_true",
                    help="--pocket-clear: tasks.queues.in_line true on the on side (the off side never has it)")
    ap.add_argument("--off-as-is", action="store_true",
                    help="--pocket-clear: the off side keeps clear_after N too (compares two builds, e.g. --off-build of main)")
    ap.add_argument("--off-build", help="--pocket-clear: the build of the off side (default --build)")
    ap.add_argument("--stall-configs", nargs="+",
                    default=["config/large_warehouse_lifelong.yaml", "config/large_oneway_lifelong.yaml"])
    ap.add_argument("--swap-after", type=int, default=30)
    ap.add_argument("--head-after", type=int, default=60)
    ap.add_argument("--load-cost", type=int, default=0)
    ap.add_argument("--pocket-cost", type=int, default=100)
    ap.add_argument("--drop-hints", action="store_true", help="--stall-rules: tasks.urgency.drop_hints on the on side")
    ap.add_argument("--mouth-cost", type=int, default=0,
                    help="--stall-rules: tasks.urgency.mouth_cost on the on side (tasks/stub_mouths.hpp)")
    ap.add_argument("--sticky", action="store_true", help="--stall-rules: tasks.urgency.sticky on the on side")
    ap.add_argument("--against-rules", action="store_true",
                    help="--stall-rules: the off side keeps the on side's rules without mouth_cost and sticky "
                         "(either given), else without drop_hints")
    ap.add_argument("--urgency-configs", nargs="+",
                    default=["config/large_warehouse_lifelong.yaml", "config/large_oneway_lifelong.yaml",
                             "config/small_warehouse_lifelong.yaml"])
    ap.add_argument("--queue-variants", nargs="+", metavar="JSON",
                    help="tasks.queues overrides, e.g. '{\"leavers_first\": true}', each against the config as is "
                         "(--clear-configs, --seeds, --large-ticks-list, --jobs)")
    ap.add_argument("--task-variants", nargs="+", metavar="JSON",
                    help="tasks overrides merged key by key, e.g. '{\"urgency\": {\"escalate_after\": 150}}', each "
                         "against the config as is (--clear-configs, --seeds, --large-ticks-list, --jobs)")
    ap.add_argument("--large-ticks-list", default=None, help="--queue-variants: tick counts, e.g. 1000,2000 (default --large-ticks)")
    ap.add_argument("--planner", action="append", default=[], metavar="KEY=VALUE",
                    help="a planner key set in every run (YAML value), e.g. free_first=true; repeatable")
    ap.add_argument("--jobs", type=int, default=1, help="--queue-variants: runs at once")
    a = ap.parse_args()
    if a.large_ticks_list is None:
        a.large_ticks_list = str(a.large_ticks)
    global QUEUES, EXECUTOR, SOLVER
    QUEUES, EXECUTOR, SOLVER = a.queues, a.executor, a.solver
    for kv in a.planner:
        k, _, v = kv.partition("=")
        PLANNER[k] = yaml.safe_load(v)
    dflt = "the config's"
    print(f"# solver: {SOLVER or dflt}, executor: {EXECUTOR or dflt}, "
          f"expansions per step: {dflt + ' budget' if a.long_k else a.expansions}"
          + (", queues" if QUEUES else ""), flush=True)
    build = os.path.abspath(a.build)
    tmp = tempfile.mkdtemp(prefix="bench_rules_")
    clean = True
    if a.station_closure:
        return station_closure(a, build, tmp)
    if a.urgency:
        return urgency(a, build, tmp)
    if a.shipped_k:
        return shipped_k(a, build, tmp)
    if a.long_k:
        return long_k(a, build, tmp)
    if a.admission:
        return admission(a, build, tmp)
    if a.stall_rules:
        return stall_rules(a, build, tmp)
    if a.pocket_clear:
        return pocket_clear(a, build, tmp)
    if a.queue_variants:
        return queue_variants(a, build, tmp)
    if a.task_variants:
        return task_variants(a, build, tmp)
    print("| warehouse | rules | ticks | errands/tick | vs off | K (stall max / p99) | errand ticks max | closure changes | zone holds | planner restarts | violations | jumps+resyncs |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, base, tick_opt, closure, zones in WAREHOUSES:
        if (a.skip_large and "large" in name) or (a.skip_small and "small" in name):
            continue
        ticks = getattr(a, tick_opt)
        closure_rule = [{"edges": closure, "begin": round(0.2 * ticks), "end": round(0.5 * ticks)}]
        one_way_rule = [{"edges": closure[:1], "begin": round(0.2 * ticks), "end": round(0.5 * ticks)}]
        zone_rule = None
        for z in zones:  # a zone holding no two random starts
            m, err = run(build, base, os.path.join(tmp, "probe"), 1, a.expansions,
                         {"sumo": False, "watch_lanes": False, "zones": [{"id": "z", "edges": z}]})
            if m is not None:
                zone_rule = [{"id": "z", "edges": z}]
                break
        if zone_rule is None:
            print(f"# {name}: every candidate zone holds two starts: {err}", file=sys.stderr)
            return 1
        variants = [("off", {}), ("closure", {"closures": closure_rule}),
                    ("one-way closure (" + closure[0] + ")", {"closures": one_way_rule}), ("zone", {"zones": zone_rule}),
                    ("both", {"closures": closure_rule, "zones": zone_rule})]
        base_rate = None
        for label, extra in variants:
            rules = {"sumo": False, "watch_lanes": False}
            rules.update(extra)
            out = os.path.join(tmp, name.split()[0] + "_" + label.split()[0])
            m, err = run(build, base, out, ticks, a.expansions, rules)
            if m is None:
                print(f"# {name} {label}: {err}", file=sys.stderr)
                return 1
            rate = m["lifelong"]["errandThroughput"]
            base_rate = rate if base_rate is None else base_rate
            r = m.get("rules", {})
            jr = m["teleports_or_jumps"]
            clean = clean and run_clean(m)
            what = label + (f" ({','.join(zone_rule[0]['edges'])})" if "zones" in extra else "")
            print(f"| {name} | {what} | {m['ticks']} | {rate:.3f} | {rate / base_rate if base_rate else 0:.2f} | "
                  f"{k_cols(m)} | {r.get('closure_changes', 0)} | {r.get('zone_holds', 0)} | "
                  f"{r.get('replans', 0)} | {m['violations']} | {jr} |", flush=True)
    if not a.skip_one_way:  # the same layout with one-way picking aisles, rules off
        base_rate = None
        for label, base in [("two-way aisles", "config/large_warehouse_lifelong.yaml"),
                            ("one-way aisles", "config/large_oneway_lifelong.yaml")]:
            out = os.path.join(tmp, "large_" + label.split()[0])
            m, err = run(build, base, out, a.large_ticks, a.expansions, {"sumo": False, "watch_lanes": False})
            if m is None:
                print(f"# large {label}: {err}", file=sys.stderr)
                return 1
            rate = m["lifelong"]["errandThroughput"]
            base_rate = rate if base_rate is None else base_rate
            jr = m["teleports_or_jumps"]
            clean = clean and run_clean(m)
            print(f"| large (200 AGVs) | {label}, rules off | {m['ticks']} | {rate:.3f} | "
                  f"{rate / base_rate if base_rate else 0:.2f} | {k_cols(m)} | 0 | 0 | "
                  f"{m.get('rules', {}).get('replans', 0)} | {m['violations']} | {jr} |", flush=True)
    print("all runs clean (0 collisions, 0 violations, 0 jumps/re-syncs, no error)" if clean else "NOT ALL RUNS CLEAN")
    return 0 if clean else 1


if __name__ == "__main__":
    sys.exit(main())
