#!/usr/bin/env python3
"""Same decisions before and after a refactor of the SUMO controller's lifelong mode:
deterministic rtlacam-sumo runs (planner.budget_ms 0, a fixed number of expansions per SUMO
step, fixed seeds) with two builds; metrics.json, the lifelong log and plan.txt compared once
the timing fields are taken out (the grid side's counterpart: same_decisions.py).

    scripts/same_decisions_sumo.py BEFORE/apps/rtlacam-sumo AFTER/apps/rtlacam-sumo [--ticks 250]

Prints one line per run (identical / DIFFERENT: the first differing key) and exits 1 on any
difference. The runs cover lockstep and the ADG executors, delays, station queues (stall
hints on), batteries with charging, a rotation solver and traffic rules, and one-shot runs
(stuck replans, rules).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from same_decisions import first_diff  # noqa: E402  (the grid twin's comparison, shared)
from bench_twin import absolute  # noqa: E402  (the YAML's net paths made absolute)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

DELAYS = {"kind": "bernoulli", "p": 0.01, "duration_s": [1, 5], "seed": 0}
QUEUES = {"tasks": {"queues": {"capacity": 1, "length": 4}}}

# (name, config, overrides merged into the YAML)
RUNS = [
    ("small lifelong lockstep", "config/small_warehouse_lifelong.yaml", {}),
    ("small lifelong adg-follow p0.01", "config/small_warehouse_lifelong.yaml",
     {"run": {"executor": "adg-follow"}, "delays": DELAYS}),
    ("small lifelong adg", "config/small_warehouse_lifelong.yaml", {"run": {"executor": "adg"}}),
    ("small queues lockstep", "config/small_warehouse_lifelong.yaml", QUEUES),
    ("small queues adg-follow", "config/small_warehouse_lifelong.yaml", dict(QUEUES, run={"executor": "adg-follow"})),
    ("small charging", "config/small_charging_lifelong.yaml", {}),
    ("small charging adg-follow", "config/small_charging_lifelong.yaml", {"run": {"executor": "adg-follow"}}),
    # A fast drain (bench_charging.py's aggressive settings): charging errands and battery hints.
    ("small charging drained", "config/small_charging_lifelong.yaml",
     {"fleet": {"count": 8, "battery": {"per_m_wh": 1.5, "critical": 0.25}}, "run": {"executor": "adg-follow"}}),
    ("small pibt-rot lockstep", "config/small_warehouse_lifelong.yaml", {"planner": {"solver": "pibt-rot"}}),
    ("small epibt adg-follow", "config/small_warehouse_lifelong.yaml",
     {"planner": {"solver": "epibt"}, "run": {"executor": "adg-follow"}}),
    ("small wppl lockstep", "config/small_warehouse_lifelong.yaml", {"planner": {"solver": "wppl"}}),
    ("small pibt-rot adg-follow", "config/small_warehouse_lifelong.yaml",
     {"planner": {"solver": "pibt-rot"}, "run": {"executor": "adg-follow"}}),
    ("small rules lockstep", "config/small_rules_lifelong.yaml", {}),
    ("small oneway", "config/small_oneway_lifelong.yaml", {}),
    ("large queues pibt-rot", "config/large_warehouse_queues.yaml", {}),
    ("large parking", "config/large_warehouse_parking.yaml", {}),
    # One-shot runs (no lifelong.json): the step budget's paths outside the lifelong mode,
    # with stuck replans and rules restarts charged to the next SUMO step.
    ("small one-shot adg-follow", "config/small_warehouse_agv.yaml", {}),
    ("small one-shot lockstep", "config/small_warehouse.yaml", {}),
    ("large one-shot adg-follow", "config/large_warehouse_agv.yaml", {}),
    ("large one-shot stuck replans", "config/large_warehouse_agv.yaml",
     {"delays": {"kind": "bernoulli", "p": 0.05, "duration_s": [3, 25], "seed": 1}, "run": {"replan_on_stuck": True}}),
    ("small one-shot stuck", "config/small_warehouse_stuck.yaml", {}),
    ("small one-shot rules", "config/small_rules.yaml", {}),
]


# lifelong.json keys and metrics.json "lifelong" keys added by issue 20 (the task layer's
# counts in the log, the prefetch's BFS work in the metrics).
NEW_LOG_KEYS = ("maxErrandTicks", "queues", "parking")
NEW_METRICS_KEYS = ("precomputePops",)


def merge(a, b):
    for k, v in b.items():
        if isinstance(v, dict) and isinstance(a.get(k), dict):
            merge(a[k], v)
        else:
            a[k] = v
    return a


def config(base, over, ticks, expansions, out):
    cfg = absolute(yaml.safe_load(open(os.path.join(ROOT, base))), base)
    cfg["sumo"]["outputs"] = {"fcd": False, "tripinfo": False, "summary": False, "collision": True}
    cfg = merge(cfg, json.loads(json.dumps(over)))
    cfg["planner"].update({"budget_ms": 0, "expansions": expansions})
    cfg["run"].update({"max_ticks": ticks, "progress_s": 0})
    cfg["output"] = {"dir": out, "plan": True, "congestion": False}
    with open(out + ".yaml", "w") as f:
        yaml.safe_dump(cfg, f)
    return out + ".yaml"


def timing(key):
    """Keys whose values are times (or come from times): they differ run to run."""
    k = key.lower()
    return ("ms" in k or "stats" in k or k.endswith("_s") and k not in ("tick_s", "sim_s") or
            k in ("plannertimes", "stepsoverbudget", "stepsoverbudgetcpu", "real_time_factor",
                  "controller_to_sumo_ratio", "config", "problem", "wall", "comp_time"))


def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if not timing(k)}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x


def run(binary, base, over, ticks, expansions, out):
    cfg = config(base, over, ticks, expansions, out)
    r = subprocess.run([os.path.abspath(binary), cfg], capture_output=True, text=True)
    if not os.path.exists(os.path.join(out, "metrics.json")):
        sys.exit(f"same_decisions_sumo: {binary} {cfg}: exit {r.returncode}: {r.stderr.strip()[-300:]}")
    m = json.load(open(os.path.join(out, "metrics.json")))
    life = os.path.join(out, "lifelong.json")
    log = json.load(open(life)) if os.path.exists(life) else {}  # one-shot: none
    plan = [l for l in open(os.path.join(out, "plan.txt")) if not l.startswith("comp_time=")]
    return {"metrics": strip(m), "lifelong": strip(log), "plan": plan}, m


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--ticks", type=int, default=250)
    ap.add_argument("--expansions", type=int, default=20, help="planner expansions per SUMO step")
    ap.add_argument("--only", default="", help="only the runs whose name contains this")
    ap.add_argument("--out", help="keep the runs here (default: a temporary folder)")
    a = ap.parse_args()
    work = os.path.abspath(a.out) if a.out else tempfile.mkdtemp(prefix="same_decisions_sumo_")
    os.makedirs(work, exist_ok=True)
    runs = [r for r in RUNS if a.only in r[0]]
    bad = 0
    for name, base, over in runs:
        slug = name.replace(" ", "_")
        x, _ = run(a.before, base, over, a.ticks, a.expansions, os.path.join(work, slug + "-before"))
        y, m = run(a.after, base, over, a.ticks, a.expansions, os.path.join(work, slug + "-after"))
        # Fields a newer build writes that an older one did not (compared when both have them).
        fixed = [k for k in NEW_LOG_KEYS if k in y["lifelong"] and k not in x["lifelong"]]
        for k in fixed:
            y["lifelong"].pop(k)
        newm = [k for k in NEW_METRICS_KEYS if k in y["metrics"].get("lifelong", {}) and k not in x["metrics"].get("lifelong", {})]
        for k in newm:
            y["metrics"]["lifelong"].pop(k)
        fixed += ["metrics " + k for k in newm]
        same = json.dumps(x, sort_keys=True) == json.dumps(y, sort_keys=True)
        ll = m.get("lifelong", {})
        extra = f"{m['battery']['charging_errands']} charging errands, " if "battery" in m else ""
        extra += f"{m['rules']['replans']} rule replans, " if m.get("rules", {}).get("replans") else ""
        print(f"{name:34s} {m['ticks']} ticks, {ll.get('numErrandFinished')} errands, {ll.get('epochs')} epochs, {extra}"
              f"error '{m['error']}': " + ("identical" if same else "DIFFERENT at " + str(first_diff(x, y))) +
              (f" (before had no {', '.join(fixed)})" if fixed else ""), flush=True)
        bad += not same
    print(f"same_decisions_sumo: {len(runs) - bad}/{len(runs)} identical (timing fields aside; files in {work})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
