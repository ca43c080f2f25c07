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


def test_lifelong_takes_every_task_layer_option_of_the_yaml():
    # The controller's tasks.* and fleet.battery keys, through the one task-layer factory
    # (tasks/task_layer.hpp): the same log as rtlacam-lifelong with the same options.
    app = os.path.join(ROOT, "build", "apps", "rtlacam-lifelong")
    if not os.path.exists(app):
        pytest.skip("rtlacam-lifelong not built in build/")
    g = rtlacam.load_map(os.path.join(os.path.dirname(PROBLEM), "maps", "random-32-32-20.map"))
    cells = [v for v in range(0, g.size, g.size // 8)][:8]
    lines = open(os.path.join(os.path.dirname(PROBLEM), "agents", "random_32_32_20_100.agents")).read().split()
    park = [int(x) for x in lines[22:30]]  # LoRR cells (row x width + column) of agents 21..28
    park_v = [g.at(c % g.width, c // g.width) for c in park]
    args = dict(solver="rtlacam", steps=120, budget_ms=1000, budget_expansions=20, seed=1, agents=20, mode="pool",
                assigner="hungarian", k_nearest=4, pool_size=5, reassign=True,
                queues=dict(capacity=1, length=2, admission=-1, fifo=False), urgency=dict(stalls="auto", battery=True, swap_after=5, head_after=10, load_cost=2, drop_hints=True,
                                                                                           pocket_cost=50),
                parking=park_v, battery=dict(capacity_wh=100, initial=0.45, per_m_wh=0.5, task_check=False, rematch=False,
                                             charge_w=36000), chargers=cells)
    log = rtlacam.lifelong(PROBLEM, **args)
    assert log["mode"] == "pool" and log["assigner"] == "hungarian" and log["reassign"] is True
    assert log["queues"]["maxHeading"] <= 1
    assert log["parking"]["idleAtEnd"] >= 10 and log["parking"]["parkedAtEnd"] >= 4
    assert "battery" in log and log["numPlannerErrors"] == 0
    parking_file = os.path.join(os.environ.get("TMPDIR", "/tmp"), "rtlacam_py_parking.txt")
    chargers_file = os.path.join(os.environ.get("TMPDIR", "/tmp"), "rtlacam_py_chargers.txt")
    with open(parking_file, "w") as f:
        f.write("\n".join(map(str, [8] + park)) + "\n")
    with open(chargers_file, "w") as f:
        f.write("\n".join(map(str, [8] + [g.xy(v)[1] * g.width + g.xy(v)[0] for v in cells])) + "\n")
    out = subprocess.run([app, "--problem", PROBLEM, "--solver", "rtlacam", "--steps", "120", "--budget-ms", "1000",
                          "--budget-expansions", "20", "--seed", "1", "--agents", "20", "--mode", "pool",
                          "--assigner", "hungarian", "--k-nearest", "4", "--pool-size", "5", "--reassign",
                          "--queue-capacity", "1", "--queue-length", "2", "--queue-admission", "-1", "--no-queue-fifo",
                          "--urgency", "--stall-swap-after", "5", "--stall-head-after", "10",
                          "--station-load-cost", "2", "--drop-hints", "--pocket-cost", "50", "--parking", parking_file, "--battery-capacity-wh", "100",
                          "--battery-initial", "0.45", "--battery-per-m-wh", "0.5", "--battery-no-task-check",
                          "--battery-no-rematch", "--battery-charge-w", "36000", "--chargers", chargers_file, "--quiet"],
                         capture_output=True, text=True, check=True)
    ref = json.loads(out.stdout)
    for k in ("numTaskFinished", "numErrandFinished", "maxErrandTicks", "queues", "parking", "battery", "stallTicks"):
        assert log[k] == ref[k], k
    # Each part reaches the run: without the queues, parking or the task check off, the run differs.
    def sig(x):
        return [x[k] for k in ("events", "maxErrandTicks", "queues", "parking", "battery")]
    for off in (dict(queues=None), dict(parking=None), dict(battery=dict(args["battery"], task_check=True))):
        assert sig(rtlacam.lifelong(PROBLEM, **dict(args, **off))) != sig(log), off
    with pytest.raises(ValueError, match="queues: unknown key 'cap'"):
        rtlacam.lifelong(PROBLEM, steps=5, agents=5, queues=dict(cap=1))
    with pytest.raises(ValueError, match="queues.admission: must be >= capacity"):
        rtlacam.lifelong(PROBLEM, steps=5, agents=5, queues=dict(capacity=3, admission=2))
    with pytest.raises(ValueError, match="urgency.swap_after: must be >= 0"):
        rtlacam.lifelong(PROBLEM, steps=5, agents=5, urgency=dict(swap_after=-1))
    # tasks.queues clear_after / in_line / leavers_first and tasks.urgency.escalate_after reach the grid too.
    log = rtlacam.lifelong(PROBLEM, steps=30, agents=20, urgency=dict(escalate_after=10),
                           queues=dict(capacity=1, clear_after=20, in_line=True, leavers_first=True))
    assert log["numErrandFinished"] > 0 and log["numPlannerErrors"] == 0 and log["queues"]["maxHeading"] <= 1
    with pytest.raises(ValueError, match="queues.leavers_first: needs clear_after > 0"):
        rtlacam.lifelong(PROBLEM, steps=5, agents=5, queues=dict(capacity=1, leavers_first=True))
    # jam_after and one_way (session 39) reach the grid too (as rtlacam-lifelong's --queue-jam-after,
    # --queue-one-way): stations clear, and the one-way lanes change the run.
    plain = rtlacam.lifelong(PROBLEM, steps=60, agents=40, queues=dict(capacity=1))
    log = rtlacam.lifelong(PROBLEM, steps=60, agents=40, queues=dict(capacity=1, jam_after=2))
    assert log["numErrandFinished"] > 0 and log["queues"]["jamClearings"] > 0 and plain["queues"]["jamClearings"] == 0
    with pytest.raises(ValueError, match="queues.jam_after: must be >= 0"):
        rtlacam.lifelong(PROBLEM, steps=5, agents=5, queues=dict(capacity=1, jam_after=-1))
    log = rtlacam.lifelong(PROBLEM, steps=60, agents=40, queues=dict(capacity=1, one_way=True))
    assert log["numPlannerErrors"] == 0 and log["numErrandFinished"] > 0 and log["events"] != plain["events"]
    with pytest.raises(ValueError, match="mode: must be roundrobin or pool"):
        rtlacam.lifelong(PROBLEM, steps=5, agents=5, mode="fifo")


def test_lifelong_cli_sets_the_two_urgency_hints_apart_as_python_does():
    # --urgency switches both hints; --urgency-stalls / --urgency-battery one each, as the YAML's
    # tasks.urgency.{stalls, battery} and Python's urgency=dict(stalls, battery) do.
    app = os.path.join(ROOT, "build", "apps", "rtlacam-lifelong")
    if not os.path.exists(app):
        pytest.skip("rtlacam-lifelong not built in build/")
    g = rtlacam.load_map(os.path.join(os.path.dirname(PROBLEM), "maps", "random-32-32-20.map"))
    lorr = [1, 100, 200, 300, 400, 501, 600, 701]  # free cells (row x width + column)
    chargers_file = os.path.join(os.environ.get("TMPDIR", "/tmp"), "rtlacam_py_urgency_chargers.txt")
    with open(chargers_file, "w") as f:
        f.write("\n".join(map(str, [len(lorr)] + lorr)) + "\n")
    battery = dict(capacity_wh=100, initial=0.45, per_m_wh=0.5, charge_w=36000)
    args = dict(solver="rtlacam", steps=120, budget_ms=1000, budget_expansions=20, seed=1, agents=20, mode="pool",
                battery=battery, chargers=[g.at(c % g.width, c // g.width) for c in lorr])
    cli = [app, "--problem", PROBLEM, "--solver", "rtlacam", "--steps", "120", "--budget-ms", "1000",
           "--budget-expansions", "20", "--seed", "1", "--agents", "20", "--mode", "pool",
           "--battery-capacity-wh", "100", "--battery-initial", "0.45", "--battery-per-m-wh", "0.5",
           "--battery-charge-w", "36000", "--chargers", chargers_file, "--quiet"]

    def sig(x):
        return [x[k] for k in ("numTaskFinished", "numErrandFinished", "maxErrandTicks", "battery", "stallTicks")]

    logs = {}
    for name, hints, flags in (("stalls", dict(stalls=True, battery=False), ["--urgency-stalls"]),
                               ("battery", dict(stalls=False, battery=True), ["--urgency", "--no-urgency-stalls"])):
        logs[name] = rtlacam.lifelong(PROBLEM, **dict(args, urgency=hints))
        ref = json.loads(subprocess.run(cli + flags, capture_output=True, text=True, check=True).stdout)
        assert sig(logs[name]) == sig(ref), name
    assert sig(logs["stalls"]) != sig(logs["battery"])
