#!/usr/bin/env python3
"""Closed-loop executors against the physical bound (issue 21).

For each scenario config and delay probability p (Bernoulli per AGV per tick, stops of 1-5 s)
runs lockstep, adg and adg-follow (physics of the config) and prints makespan (one-shot) or
errands per tick (lifelong), the bound and their ratio, plus errors / collisions / overshoot.
The bound is fixed by the instance, the same for every executor and plan:
- one-shot: metrics.json bound_ticks (controller/instance_bound.hpp), the slowest AGV alone on a
  shortest way -- lockstep: in moves (lockstep_bound_ticks); the others: with the vType's
  kinematics (physical_bound_ticks). The plan's bound (plan_bound_ticks: every AGV alone on
  its planned path, which moves with the execution) is printed beside it;
- lifelong: lifelong.freeFlowBound (tasks/free_flow.hpp), every AGV alone on shortest paths
  along its errand sequence (errands per tick over it: errandThroughputOverFreeFlow), priced
  over every errand handed out (the open ones at the end too); the bound over the finished
  errands alone, biased to the short ones, is printed beside it.
A config without a fleet.vtype (the lifelong ones) gets the *_agv configs' kinematics.

Then, per row, the ratio over lockstep's at the same p and over the same executor's at p = 0.

An executor may carry run switches after a colon, e.g. `adg-follow:gap_handover=false` (the
same binary with a mechanism off: a before/after in one call). `--seeds S1 S2 ...` runs each
instance with fleet.seed S and tasks.seed S + 1 (other start and goal draws); the ratio table
then also gives the geometric mean over the seeds. `--expansions E` replaces the wall-clock
planner budget by E expansions per SUMO step (deterministic plans, whatever the box's load).

  scripts/bench_closed_loop.py [--build build] [--configs small_warehouse_agv.yaml ...]
                               [--ps 0 0.01] [--executors lockstep adg adg-follow[:key=value,...]]
                               [--max-ticks N] [--seeds 1 2 3] [--expansions 50]
"""
import itertools
import math
import re
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_executor import yaml_variant, sumo_run  # noqa: E402


# The AGV kinematics of the shipped *_agv configs, for a config without a vtype (the
# lifelong ones): the physical executors and the bound then use the same physics.
AGV_VTYPE = "  vtype: {length: 0.8, width: 0.6, min_gap: 0.1, accel: 0.5, decel: 1.0, max_speed: 1.0}\n"


def with_agv_vtype(path):
    s = open(path).read()
    if "vtype:" not in s:
        open(path, "w").write(s.replace("fleet:\n", "fleet:\n" + AGV_VTYPE, 1))


def set_run_keys(cfg, sets, seed, expansions):
    """`key=value,...` into the config's run section (`section.key=value`: that section); the fleet / tasks seeds; a deterministic budget."""
    s = open(cfg).read()
    for kv in filter(None, sets.split(",")):
        k, v = kv.split("=")
        sec, _, key = k.rpartition(".")  # "rules.plan_zones=false": another section's key
        sec = sec or "run"
        if f"\n{sec}:\n" not in s:
            s = s.replace("output:\n", f"{sec}:\noutput:\n", 1)
        s = s.replace(f"\n{sec}:\n", f"\n{sec}:\n  {key or k}: {v}\n", 1)
    if seed is not None:
        s = re.sub(r"(\nfleet:\n(?:  .*\n)*?  seed: )\d+", rf"\g<1>{seed}", s, 1)
        s = re.sub(r"(\ntasks:\n(?:  .*\n)*?  seed: )\d+", rf"\g<1>{seed + 1}", s, 1)
    if expansions:
        s = re.sub(r"  budget_ms: [0-9.]+\n", f"  budget_ms: 0\n  expansions: {expansions}\n", s, 1)
    open(cfg, "w").write(s)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--configs", nargs="+", default=["small_warehouse_agv.yaml", "large_warehouse_agv.yaml"])
    ap.add_argument("--ps", nargs="+", type=float, default=[0, 0.01])
    ap.add_argument("--executors", nargs="+", default=["lockstep", "adg", "adg-follow"])
    ap.add_argument("--window", type=int, default=16)
    ap.add_argument("--max-ticks", type=int, default=None)
    ap.add_argument("--seeds", nargs="+", type=int, default=[None], help="fleet.seed (tasks.seed: +1); default: the config's")
    ap.add_argument("--expansions", type=int, default=0, help="planner expansions per SUMO step instead of budget_ms")
    ap.add_argument("--split", action="store_true", help="also print where the AGV-steps go (metrics.json executor.split)")
    a = ap.parse_args()
    split_of = {}  # (config, p, executor) -> [category -> agent-s summed over the seeds, agent-plan-steps, moves from rest]
    tmp = tempfile.mkdtemp(prefix="bench_closed_")
    per_step_of = {}  # (config, p, executor) -> ticks per plan step over the seeds (one-shot, solved)
    ratio_of = {}  # (config, seed, p, executor) -> makespan/bound (one-shot) or throughput/bound (lifelong)
    print("| config | seed | p | executor | makespan or errands/tick | bound | ratio | plan's bound | solved | error | "
          "collisions | overshoot m | replans | ticks / plan step | wall s |")
    print("|---|---:|---:|---|---:|---:|---:|---:|---|---|---:|---:|---:|---:|---:|")
    for c, seed, p, ex in itertools.product(a.configs, a.seeds, a.ps, a.executors):
        name, _, sets = ex.partition(":")
        cfg = yaml_variant(c, name, p, window=a.window, max_ticks=a.max_ticks)
        with_agv_vtype(cfg)
        set_run_keys(cfg, sets, seed, a.expansions)
        try:
            m = sumo_run(a.build, cfg, os.path.join(tmp, re.sub(r"[^\w.-]", "_", f"{c}_{seed}_{ex}_{p}")))
        except FileNotFoundError:  # no metrics.json: the instance was refused (e.g. a zone holding two goals)
            print(f"| {c} | {seed if seed is not None else '-'} | {p} | {ex} | - | - | - | - | - | refused (no metrics.json) | - | - | - | - | - |",
                  flush=True)
            continue
        life = m.get("lifelong")
        if life:
            val, bound, ratio = life["errandThroughput"], life["freeFlowBound"], life["errandThroughputOverFreeFlow"]
            plan = life["throughputBound"]
            fin = life.get("freeFlowBoundFinishedOnly")
        else:
            val, bound, ratio = m["makespan"], m["bound_ticks"], m["makespan_over_bound"]
            plan = m["plan_bound_ticks"]
            fin = None
        # Ticks per committed plan step (one-shot): what executing the plan costs, apart from
        # how long the plan is. Plan lengths of one instance vary by up to 1.4x between runs
        # (the real-time search's timing differs per executor and p), lockstep's is 1 by
        # construction (session 37).
        commits = m["executor"].get("commits", 0)
        per_step = f"{m['makespan'] / commits:.3f}" if not life and commits else "-"
        # an unfinished one-shot run has no makespan to compare
        ratio_of[(c, seed, p, ex)] = (ratio if life or m["solved"] else None, bool(life))
        if per_step != "-" and m["solved"]:
            per_step_of.setdefault((c, p, ex), []).append(m["makespan"] / commits)
            if "split" in m["executor"]:
                acc = split_of.setdefault((c, p, ex), [{}, 0, 0, 0, 0])
                for k, n in m["executor"]["split"].items():
                    acc[0][k] = acc[0].get(k, 0) + n * m["step_length"]
                acc[1] += m["agents"] * commits
                acc[2] += m["executor"]["starts_from_rest"]
                acc[3] += m["executor"]["starved"]["starts"]
                acc[4] += m["executor"]["starved"]["steps"] * m["step_length"]
        print(f"| {c} | {seed if seed is not None else '-'} | {p} | {ex} | {val:.4g} | {bound:.4g}{f' ({fin:.4g} finished only)' if fin else ''} | {ratio:.3f} | {plan:.4g} | "
              f"{m['solved']} | {m['error'][:60]} | {m['collisions']} | {m['executor'].get('overshoot_m', 0):.2g} | "
              f"{m['executor'].get('replans', 0)} | {per_step} | {m['_wall']:.1f} |", flush=True)
    # The targets (issue 21), against baselines of this run: at p = 0 the executor's ratio over
    # lockstep's (one-shot: makespan/bound, lower is better; lifelong: lockstep's
    # errands per tick / bound over the executor's, so > 1 is worse alike); at p > 0, the same
    # executor's ratio over its own at p = 0 (the same orientation).
    print("\n| config | seed | p | executor | vs lockstep (same p) | vs itself at p = 0 |\n|---|---:|---:|---|---:|---:|")
    rels = {}  # (config, p, executor, which) -> ratios over the seeds
    for (c, seed, p, ex), (r, life) in ratio_of.items():
        def rel(base, which):
            if base is None or r is None or base[0] is None or not r or not base[0]:
                return "-"
            x = base[0] / r if life else r / base[0]
            rels.setdefault((c, p, ex, which), []).append(x)
            return f"{x:.3f}"
        print(f"| {c} | {seed if seed is not None else '-'} | {p} | {ex} | {rel(ratio_of.get((c, seed, p, 'lockstep')), 0)} | "
              f"{rel(ratio_of.get((c, seed, 0.0, ex)), 1)} |")
    if len(a.seeds) > 1:
        print("\nGeometric means over the seeds (runs with a ratio on both sides only):")
        print("| config | p | executor | vs lockstep (same p) | vs itself at p = 0 | seeds | ticks / plan step |\n|---|---:|---|---:|---:|---:|---:|")
        for c in a.configs:
            for p in a.ps:
                for ex in a.executors:
                    g = [rels.get((c, p, ex, w), []) for w in (0, 1)]
                    gm = ["-" if not x else f"{math.exp(sum(map(math.log, x)) / len(x)):.3f}" for x in g + [per_step_of.get((c, p, ex), [])]]
                    print(f"| {c} | {p} | {ex} | {gm[0]} | {gm[1]} | {max(len(g[0]), len(g[1]))} | {gm[2]} |")

    if a.split and split_of:
        # Each AGV's SUMO steps up to its last arrival, by what held it (controller/driver.hpp,
        # DriveStats::Split), in agent-seconds per agent per committed plan step (solved
        # one-shot runs, summed over the seeds): lock-step spends at most 1 s per plan step.
        keys = list(split_of)
        cats = [k for k in next(iter(split_of.values()))[0] if any(split_of[x][0].get(k, 0) for x in keys)]
        print("\nWhere the AGV-steps go (s per agent per plan step, up to each AGV's last arrival; solved runs):")
        print("| category | " + " | ".join(f"{ex} p={p}" for (_, p, ex) in keys) + " |")
        print("|---|" + "---:|" * len(keys))
        for k in cats:
            print(f"| {k} | " + " | ".join(f"{split_of[x][0].get(k, 0) / split_of[x][1]:.4f}" for x in keys) + " |")
        print("| **total** | " + " | ".join(f"{sum(split_of[x][0].values()) / split_of[x][1]:.4f}" for x in keys) + " |")
        print("| moves from rest | " + " | ".join(f"{split_of[x][2] / split_of[x][1]:.4f}" for x in keys) + " |")
        print("| of them right after no_action | " + " | ".join(f"{split_of[x][3] / split_of[x][1]:.4f}" for x in keys) + " |")
        print("| no_action s before those | " + " | ".join(f"{split_of[x][4] / split_of[x][1]:.4f}" for x in keys) + " |")


if __name__ == "__main__":
    main()
