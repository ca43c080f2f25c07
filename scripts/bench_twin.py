#!/usr/bin/env python3
"""SUMO against its grid twin, each over its own free-flow bound (issue 20).

For each warehouse config (lifelong, SUMO), solver and delay probability p, two runs in one
invocation:
  - SUMO: the config with physical AGVs (the vType of the *_agv configs), the executor given
    (default adg-follow), Bernoulli stops of 1-5 s at p per AGV per tick;
  - its grid twin: rtlacam-lifelong on the same gridified net (rtlacam-gridify --map), the
    same fleet size, pick-up -> drop tasks between the same stations, the same pool, station
    queues and priorities, the same executor and delay model at one step per tick.
Both sides plan with a fixed number of expansions (deterministic decisions; E per SUMO step
in SUMO, E x steps-per-tick per grid step), so the comparison is about execution, not CPU.
Rotation solvers (pibt-rot, epibt, wppl) turn in fleet.turn_s (one tick) in SUMO and in one
step (--action-model rotation) in the twin, with the controller's planner.rotation defaults on
both sides; a row "SOLVER+OPTION" changes one (+arrows, +unguided: guidance arrows, none;
+distance, +age: epibt's priority; +pocket, any solver: pocket_cost 100). In the twin their planned steps run on the same executor and delay
model as cell plans, robots turning in place before they move (executor/graph_execution.hpp "Headings").

Each side reports its free-flow bound (tasks/free_flow.hpp): every AGV alone on its errand
sequence along shortest paths, a cell per step on the grid, the vType's rest-to-rest
trapezoid per errand in SUMO. The issue's target: SUMO's errands/tick over its bound >= 0.8 x
the twin's errands/step over its bound ("physics may cost time, congestion handling should
not get worse in SUMO"), and no collapse (last 1000 ticks >= 0.8 x the first 1000).

  scripts/bench_twin.py [--build build] [--configs config/large_warehouse_lifelong.yaml,...]
                        [--solvers rtlacam,pibt] [--p 0,0.01] [--ticks 5000] [--out DIR]
                        [--trend-window 1000] [--twin-only | --sumo-only]
A scaled-down run (fewer ticks) sets --trend-window below --ticks (e.g. 300 of 1000); the two
sides of a table can run in separate processes (--sumo-only, --twin-only), each with its own --out.
"""
import argparse
import json
import os
import random
import subprocess
import sys
import tempfile

import yaml  # PyYAML

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.environ.setdefault("SUMO_HOME", "/usr/share/sumo")
ROTATION = {"pibt-rot", "epibt", "wppl"}  # solvers that plan LoRR rotation actions
# Variants of a rotation solver: "SOLVER+OPTION+..." with OPTION one of arrows / unguided
# (guidance arrows / none), distance / age (epibt's priority). The twin mirrors the
# controller's planner.rotation defaults (controller/config.hpp): guidance arrows for every
# rotation solver (wppl since s37; rtlacam-lifelong: none for wppl); back_last on; epibt
# priority age (rtlacam-lifelong: distance).
VARIANT_OPTIONS = {"arrows": ("guidance", "arrows"), "unguided": ("guidance", "none"), "distance": ("priority", "distance"),
                   "age": ("priority", "age"), "noexit": ("pocket_exit", False),
                   "noleavers": ("leavers_first", False)}
# "+noexit" (any rotation solver): planner.rotation.pocket_exit false / --no-epibt-pocket-exit
# (epibt) or --no-rot-pocket-exit (pibt-rot, wppl): the stub jams of sessions 30-36 back
# (EpibtOptions::pocket_exit, planner/rotation/pocket_exit.hpp), for before/after rows.
# "+noleavers" (epibt): planner.rotation.leavers_first false / --no-epibt-leavers-first
# (session 36's exit rule without session 37's leavers first).
# "+pocket" (any solver): tasks.urgency.pocket_cost 100 in SUMO (PIBT ranks a move into another
# station's dead-end stub 100 moves worse; pibt-rot since s35, epibt and wppl since s36), --pocket-cost 100 in
# the twin. Not in huge_warehouse_lifelong.yaml itself: its default solver rtlacam does not
# gain with it (docs/twin_bench.md "Session 35").
POCKET_COST = 100
# "+inline" / "+noinline" (any solver): tasks.queues.in_line true / false in SUMO, --queue-in-line /
# --no-queue-in-line in the twin (tasks/station_queues.hpp QueueOptions::in_line: a station's admitted
# and queued agents re-ranked by distance every step; session 38: epibt's 1000-AGV collapse).
# "+idleclear" / "+noidleclear" (any solver): tasks.queues.idle_clear true / false in SUMO,
# --[no-]queue-idle-clear in the twin (QueueOptions::idle_clear: idle agents rest neither beside a
# dead-end station's mouth nor walk back to a rest cell they were pushed off; session 38).
# "+oneway" / "+nooneway" (any solver): tasks.queues.one_way true / false in SUMO, --[no-]queue-one-way
# in the twin (QueueOptions::one_way: queue lanes one-way towards their station; session 39).
# The three as one table: row option -> (tasks.queues key, rtlacam-lifelong flag).
QUEUE_FLAGS = {"inline": ("in_line", "queue-in-line"), "idleclear": ("idle_clear", "queue-idle-clear"),
               "oneway": ("one_way", "queue-one-way")}


def variant(name):
    """(solver, planner.rotation options) of a row name."""
    solver, *opts = name.split("+")
    rot = {}
    for o in opts:
        if o == "pocket":
            rot["pocket_cost"] = POCKET_COST
            continue
        if o in QUEUE_FLAGS or (o.startswith("no") and o[2:] in QUEUE_FLAGS):
            rot[QUEUE_FLAGS[o.removeprefix("no")][0]] = o in QUEUE_FLAGS
            continue
        if o not in VARIANT_OPTIONS or solver not in ROTATION:
            sys.exit(f"bench_twin.py: --solvers: '{name}': options (+arrows, +distance, +age) go with pibt-rot, epibt, wppl; +noleavers with epibt; +pocket with any")
        if o == "noleavers" and solver != "epibt":
            sys.exit(f"bench_twin.py: --solvers: '{name}': +noleavers goes with epibt")
        k, v = VARIANT_OPTIONS[o]
        rot[k] = v
    return solver, rot


def twin_rotation_args(solver, rot):
    args = ["--action-model", "rotation", "--guidance", rot.get("guidance", "arrows")]
    if solver == "epibt":
        args += ["--epibt-priority", rot.get("priority", "age")]
        if rot.get("pocket_exit", True) is False:
            args += ["--no-epibt-pocket-exit"]
        if rot.get("leavers_first", True) is False:
            args += ["--no-epibt-leavers-first"]
    else:
        args += ["--rot-back-last"]
        if rot.get("pocket_exit", True) is False:
            args += ["--no-rot-pocket-exit"]
    return args
VTYPE = {"length": 0.8, "width": 0.6, "min_gap": 0.1, "accel": 0.5, "decel": 1.0, "max_speed": 1.0}


def absolute(cfg, base):
    here = os.path.dirname(os.path.join(ROOT, base))
    for k in ("net", "additional"):
        if k in cfg["sumo"]:
            cfg["sumo"][k] = os.path.normpath(os.path.join(here, cfg["sumo"][k]))
    return cfg


TREND_WINDOW = 1000  # --trend-window: the first / last 1000 ticks


def windows(events, ticks, w):
    """Errands per tick over the first and the last w ticks (w capped at the run's length)."""
    w = min(w, ticks)
    first = sum(1 for t, *_ in events if t <= w) / w
    last = sum(1 for t, *_ in events if t > ticks - w) / w
    return first, last


def window_rates(events, ticks):
    first, last = windows(events, ticks, TREND_WINDOW)
    return last / first if first else 0.0


def sumo_config(base, solver, p, out, ticks, expansions, executor):
    """Writes out.yaml: the SUMO side of a row (the config with the physical vType, the row's
    solver and options, executor, Bernoulli stops at p) and returns its path."""
    cfg = absolute(yaml.safe_load(open(os.path.join(ROOT, base))), base)
    cfg["sumo"]["outputs"] = {"fcd": False, "tripinfo": False, "summary": False, "collision": True}
    cfg["fleet"]["vtype"] = VTYPE
    solver, rot = variant(solver)
    cfg["planner"].update({"solver": solver, "budget_ms": 0, "expansions": expansions})
    cfg["planner"].pop("rotation", None)  # the row's options only, as in the twin
    if "pocket_cost" in rot:
        cfg["tasks"].setdefault("urgency", {})["pocket_cost"] = rot.pop("pocket_cost")
    for key, _ in QUEUE_FLAGS.values():
        if key in rot:
            cfg["tasks"].setdefault("queues", {})[key] = rot.pop(key)
    if rot:
        cfg["planner"]["rotation"] = rot
    cfg["run"].update({"executor": executor, "max_ticks": ticks, "progress_s": 0})
    if executor != "lockstep":
        cfg["run"].setdefault("window", 16)
    cfg["delays"] = {"kind": "bernoulli", "p": p, "duration_s": [1, 5], "seed": 0} if p > 0 else {"kind": "none"}
    cfg["output"] = {"dir": out, "congestion": False}
    with open(out + ".yaml", "w") as f:
        yaml.safe_dump(cfg, f)
    return out + ".yaml"


def sumo_run(a, base, solver, p, out):
    sumo_config(base, solver, p, out, a.ticks, a.expansions, a.executor)
    r = subprocess.run([os.path.join(a.build, "apps", "rtlacam-sumo"), out + ".yaml"], capture_output=True, text=True)
    if not os.path.exists(os.path.join(out, "metrics.json")):
        return None, f"rtlacam-sumo exit {r.returncode}: {r.stderr.strip().splitlines()[-1:]}"
    m = json.load(open(os.path.join(out, "metrics.json")))
    ev = json.load(open(os.path.join(out, "lifelong.json")))["events"]
    ll = m["lifelong"]
    return {"thr": ll["errandThroughput"], "bound": ll["freeFlowBound"], "ratio": ll["errandThroughputOverFreeFlow"],
            "trend": window_rates(ev, m["ticks"]), "coll": m["collisions"], "jumps": m["teleports_or_jumps"],
            "viol": m["violations"], "error": m["error"], "ms": 1000 * m["wall_s"] / max(1, m["ticks"])}, ""


def twin_problem(a, base, work):
    """The grid twin of a SUMO lifelong config: a LoRR problem on its gridified net."""
    cfg = absolute(yaml.safe_load(open(os.path.join(ROOT, base))), base)
    name = os.path.splitext(os.path.basename(base))[0]
    tw = os.path.join(work, "twin_" + name)
    for d in ("maps", "agents", "tasks"):
        os.makedirs(os.path.join(tw, d), exist_ok=True)
    cmd = [os.path.join(a.build, "apps", "rtlacam-gridify"), cfg["sumo"]["net"], "--map", f"{tw}/maps/{name}.map",
           "--json", f"{tw}/{name}.grid.json", "-q"]
    if "additional" in cfg["sumo"]:
        cmd += ["--additional", cfg["sumo"]["additional"]]
    subprocess.run(cmd, check=True)
    j = json.load(open(f"{tw}/{name}.grid.json"))
    w = j["grid"]["width"]
    cell = [c["row"] * w + c["col"] for c in j["cells"]]
    pick = [cell[s["cell"]] for s in j["stations"] if s["kind"] == "pickup"]
    drop = [cell[s["cell"]] for s in j["stations"] if s["kind"] == "drop"]
    n = cfg["fleet"]["count"]
    rnd = random.Random(1)
    open(f"{tw}/agents/{name}.agents", "w").write(f"{n}\n" + "\n".join(map(str, rnd.sample(cell, n))) + "\n")
    open(f"{tw}/tasks/{name}.tasks", "w").write("# 2024\n100000\n" + "\n".join(
        f"{rnd.choice(pick)},{rnd.choice(drop)}" for _ in range(100000)) + "\n")
    prob = f"{tw}/{name}.json"
    json.dump({"mapFile": f"maps/{name}.map", "agentFile": f"agents/{name}.agents", "teamSize": n,
               "taskFile": f"tasks/{name}.tasks", "numTasksReveal": 1.5, "version": "2024 LoRR"}, open(prob, "w"))
    q = (cfg.get("tasks") or {}).get("queues") or {}
    keep = (cfg.get("planner") or {}).get("keep_priorities", False)
    steps_per_tick = round(cfg["run"]["tick_s"] / cfg["sumo"]["step_length"])
    return prob, q, keep, steps_per_tick, twin_urgency(cfg) if MIRROR_URGENCY else []


MIRROR_URGENCY = True  # --no-twin-urgency: the twin without the config's tasks.urgency (as before s36)


def twin_urgency(cfg):
    """rtlacam-lifelong flags for the config's tasks.urgency, as rtlacam-sumo applies it
    (controller/src/lifelong.cpp): stall hints on with station queues unless `stalls` says
    otherwise, and each rule the config sets. mouth_cost has no rtlacam-lifelong flag: the
    twin runs without it (bench_twin prints a note)."""
    t = cfg.get("tasks") or {}
    u = t.get("urgency") or {}
    stalls = u.get("stalls", "auto")
    on = ((t.get("queues") or {}).get("capacity", 0) > 0) if stalls == "auto" else bool(stalls)
    args = ["--urgency-stalls" if on else "--no-urgency-stalls"]
    for key, flag in (("swap_after", "--stall-swap-after"), ("head_after", "--stall-head-after"),
                      ("load_cost", "--station-load-cost"), ("pocket_cost", "--pocket-cost")):
        if u.get(key):
            args += [flag, str(u[key])]
    for key, flag in (("drop_hints", "--drop-hints"), ("sticky", "--sticky-stalls")):
        if u.get(key):
            args.append(flag)
    if u.get("mouth_cost"):
        print(f"# twin: tasks.urgency.mouth_cost {u['mouth_cost']} is not mirrored (rtlacam-lifelong has no flag for it)", flush=True)
    return args


def twin_run(build, twin, solver, p, out, steps, expansions, executor, agents=None):
    """One grid-twin run (rtlacam-lifelong): `expansions` per grid step, cell and rotation plans
    on `executor` with the Bernoulli delay model at p (as SUMO's delays: 1-5 steps). `agents`:
    another fleet size than the config's, with queues off and priorities reset (the layout's
    own limit; bench_twin_sweep.py --fleet)."""
    prob, q, keep, _, urgency = twin
    solver, rot = variant(solver)
    cmd = [os.path.join(build, "apps", "rtlacam-lifelong"), "--problem", prob, "--steps", str(steps),
           "--budget-ms", "1000", "--budget-expansions", str(expansions), "--solver", solver,
           "--quiet", "--out", out + ".log.json"]
    if not agents:  # the config's tasks.urgency (its own fleet only: a sweep is the bare layout)
        u = list(urgency)
        if "pocket_cost" in rot and "--pocket-cost" in u:  # the row's cost instead (CLI11 takes one)
            k = u.index("--pocket-cost")
            del u[k:k + 2]
        cmd += u
    if "pocket_cost" in rot:
        cmd += ["--pocket-cost", str(rot.pop("pocket_cost"))]
    if solver in ROTATION:  # a turn is one grid step, as fleet.turn_s defaults to one tick in SUMO
        cmd += twin_rotation_args(solver, rot)
    cmd += ["--executor", executor]
    if agents:
        cmd += ["--agents", str(agents)]
    elif q.get("capacity", 0) > 0:
        cmd += ["--queue-capacity", str(q["capacity"]), "--queue-length", str(q.get("length", 8))]
        for key, flag in QUEUE_FLAGS.values():
            on = rot.pop(key, q.get(key))  # the row's choice, else the config's (else the default)
            if on is not None:
                cmd.append(("--" if on else "--no-") + flag)
    for key, _ in QUEUE_FLAGS.values():
        rot.pop(key, None)
    if not keep or agents:
        cmd.append("--reset-priorities")
    if p > 0:
        cmd += ["--delay-kind", "bernoulli", "--delay-p", str(p), "--delay-min", "1", "--delay-max", "5"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        return None, f"rtlacam-lifelong exit {r.returncode}: {r.stderr.strip().splitlines()[-1:]}"
    j = json.loads(r.stdout)
    log = json.load(open(out + ".log.json"))
    ev = log["events"]
    return {"thr": j["errandThroughput"], "bound": j.get("freeFlowBound", 0),
            "ratio": j.get("errandThroughputOverFreeFlow", 0), "trend": window_rates(ev, j["makespan"]),
            "errors": j["numPlannerErrors"], "events": ev, "steps": j["makespan"], "team": log["teamSize"]}, ""


def main():
    ap = argparse.ArgumentParser(description="SUMO vs its grid twin over their free-flow bounds")
    ap.add_argument("--build", default="build")
    ap.add_argument("--configs", default="config/large_warehouse_lifelong.yaml,config/huge_warehouse_lifelong.yaml")
    ap.add_argument("--solvers", default="rtlacam,pibt")
    ap.add_argument("--p", default="0,0.01", help="Bernoulli stop probabilities per AGV per tick")
    ap.add_argument("--ticks", type=int, default=5000)
    ap.add_argument("--expansions", type=int, default=5, help="planner expansions per SUMO step")
    ap.add_argument("--executor", default="adg-follow", choices=["lockstep", "adg", "adg-follow"])
    ap.add_argument("--trend-window", type=int, default=1000,
                    help="ticks of the first and last windows of the collapse ratio (the issue: 1000 of 5000; scaled-down runs: less)")
    ap.add_argument("--out", help="keep runs here (default: a temporary folder)")
    ap.add_argument("--twin-only", action="store_true",
                    help="run the grid twin side only (e.g. after a change to the twin, against an earlier SUMO side)")
    ap.add_argument("--no-twin-urgency", action="store_true",
                    help="the twin without the config's tasks.urgency rules (the twin of sessions 29-35)")
    ap.add_argument("--sumo-only", action="store_true",
                    help="run the SUMO side only (e.g. its twin rows run in another process)")
    a = ap.parse_args()
    if a.twin_only and a.sumo_only:
        sys.exit("bench_twin.py: --twin-only and --sumo-only: one of them")
    a.build = os.path.abspath(a.build)
    global TREND_WINDOW, MIRROR_URGENCY
    TREND_WINDOW = a.trend_window
    MIRROR_URGENCY = not a.no_twin_urgency
    if a.trend_window <= 0:
        sys.exit(f"bench_twin.py: --trend-window {a.trend_window}: must be positive")
    a.trend_window = min(a.trend_window, a.ticks)  # a shorter run: both windows are the whole run
    for app in ("rtlacam-sumo", "rtlacam-lifelong", "rtlacam-gridify"):
        if not os.access(os.path.join(a.build, "apps", app), os.X_OK):
            sys.exit(f"bench_twin.py: {a.build}/apps/{app} is not built")
    try:
        ps = [float(x) for x in a.p.split(",")]
    except ValueError:
        sys.exit(f"bench_twin.py: --p: '{a.p}' is not a comma-separated list of numbers")
    work = os.path.abspath(a.out) if a.out else tempfile.mkdtemp(prefix="bench_twin_")
    os.makedirs(work, exist_ok=True)
    print(f"# bench_twin.py: executor {a.executor}, {a.expansions} expansions per SUMO step, {a.ticks} ticks, "
          f"last/first over {a.trend_window} ticks; files in {work}",
          flush=True)
    clean = True
    f = lambda v, k, fmt="{:.3f}": fmt.format(v[k]) if v else "-"

    def row(name, solver, p, s, t):  # printed as each pair of runs ends: a long bench shows progress
        rel = f"{s['ratio'] / t['ratio']:.2f}" if s and t and t["ratio"] > 0 else "-"
        print(f"| {name} | {solver} | {p:g} | {f(s, 'thr')} | {f(s, 'bound')} | {f(s, 'ratio')} | {f(t, 'thr')} | "
              f"{f(t, 'bound')} | {f(t, 'ratio')} | {rel} | {f(s, 'trend', '{:.2f}')} | {f(t, 'trend', '{:.2f}')} | "
              f"{f(s, 'coll', '{}')} | {f(s, 'jumps', '{}')} | {f(s, 'ms', '{:.0f}')} |", flush=True)

    print()
    print("| warehouse | solver | p | SUMO errands/tick | SUMO free-flow bound | SUMO / bound | twin errands/step | "
          f"twin free-flow bound | twin / bound | SUMO share / twin share (target >= 0.8) | SUMO last/first {a.trend_window} | "
          f"twin last/first {a.trend_window} | collisions | jumps | SUMO wall ms/tick |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|", flush=True)
    for base in a.configs.split(","):
        twin = twin_problem(a, base, work)
        name = os.path.splitext(os.path.basename(base))[0]
        for solver in a.solvers.split(","):
            for p in ps:
                tag = f"{name}_{solver}_p{p:g}"
                s, err_s = (None, "") if a.twin_only else sumo_run(a, base, solver, p, os.path.join(work, tag))
                t, err_t = (None, "") if a.sumo_only else twin_run(a.build, twin, solver, p, os.path.join(work, "twin_" + tag),
                                                                   a.ticks, a.expansions * twin[3], a.executor)
                for e in (err_s, err_t):
                    if e:
                        print(f"# {tag}: {e}", flush=True)
                        clean = False
                if s:
                    clean &= s["coll"] == 0 and s["jumps"] == 0 and s["viol"] == 0
                row(name, solver, p, s, t)
    print()
    if a.twin_only:
        print("twin only: no SUMO runs" if clean else "NOT CLEAN: see the lines above")
    else:
        print("all SUMO runs clean (0 collisions, 0 jumps, 0 violations)" if clean else "NOT CLEAN: see the lines above")
    return 0 if clean else 1


if __name__ == "__main__":
    sys.exit(main())
