"""Lifelong runs from Python: the same log rtlacam-lifelong prints."""
import json
import os
import subprocess

import pytest
import rtlacam
from conftest import DATA, ROOT

PROBLEM = os.path.join(DATA, "tasks", "lorr", "2024", "random.domain", "RANDOM-01.json")


def test_lifelong_pool_run_finishes_tasks_with_valid_moves():
    log = rtlacam.lifelong(PROBLEM, solver="rtlacam", steps=50, budget_ms=1000, budget_expansions=20, seed=1)
    assert log["numTaskFinished"] > 0
    assert log["teamSize"] == 100
    assert log["numPlannerErrors"] == 0 and "firstPlannerError" not in log
    assert log["makespan"] == 50 and len(log["events"]) > 0


def test_lifelong_equals_the_app_with_the_same_expansion_budget():
    app = os.path.join(ROOT, "build", "apps", "rtlacam-lifelong")
    if not os.path.exists(app):
        pytest.skip("rtlacam-lifelong not built in build/")
    args = dict(solver="pibt", steps=40, budget_ms=1000, budget_expansions=5, seed=3, agents=30)
    log = rtlacam.lifelong(PROBLEM, **args)
    out = subprocess.run([app, "--problem", PROBLEM, "--solver", "pibt", "--steps", "40", "--budget-ms", "1000",
                          "--budget-expansions", "5", "--seed", "3", "--agents", "30", "--quiet"],
                         capture_output=True, text=True, check=True)
    ref = json.loads(out.stdout)
    assert log["numTaskFinished"] == ref["numTaskFinished"]
    assert log["teamSize"] == ref["teamSize"] == 30


def test_lifelong_bad_input():
    with pytest.raises(ValueError, match="nope.json"):
        rtlacam.lifelong("/nope.json")
    with pytest.raises(ValueError, match="teamSize is 100"):
        rtlacam.lifelong(PROBLEM, agents=101, steps=5)
    with pytest.raises(ValueError, match="cspibt needs a policy"):
        rtlacam.lifelong(PROBLEM, solver="cspibt", steps=5)


def test_lifelong_battery_charging_keeps_agents_above_empty():
    # rtlacam-lifelong's --battery-* on the grid: half a charge emptied in 200 moves; eight
    # chargers. With charging nobody runs empty; drain only, agents do.
    battery = dict(capacity_wh=100, initial=0.5, per_m_wh=0.25, threshold=0.4, critical=0.25, target=0.9,
                   charge_w=36000)
    g = rtlacam.load_map(os.path.join(os.path.dirname(PROBLEM), "maps", "random-32-32-20.map"))
    chargers = list(range(0, g.size, g.size // 8))[:8]
    args = dict(solver="rtlacam", steps=300, budget_ms=1000, budget_expansions=20, seed=1, agents=20, chargers=chargers)
    on = rtlacam.lifelong(PROBLEM, battery=battery, **args)["battery"]
    assert on["ran_empty"] == 0 and on["min_charge"] > 0
    assert on["charging_errands"] >= 10 and on["charging_share"] > 0
    off = rtlacam.lifelong(PROBLEM, battery=dict(battery, charging=False), **args)["battery"]
    assert off["ran_empty"] > 0 and off["charging_errands"] == 0
    with pytest.raises(ValueError, match="battery.threshold: must be < target"):
        rtlacam.lifelong(PROBLEM, steps=5, agents=5, battery=dict(threshold=0.9, target=0.5, charging=False))
    with pytest.raises(ValueError, match="battery: unknown key 'volts'"):
        rtlacam.lifelong(PROBLEM, steps=5, agents=5, battery=dict(volts=24))
