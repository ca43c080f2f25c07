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


# The rotation solvers with their options (issue 20): rotation= takes the SUMO YAML's
# planner.rotation keys, naming the solver sets the action model, and unset keys take
# rtlacam-lifelong's defaults (planner/rotation_settings.hpp), so both give the same run.
# 100 agents, 60 steps: enough traffic for every key to change the run.
ROT_ARGS = dict(steps=60, budget_ms=1000, budget_expansions=5, seed=1, agents=100)
ROT_CLI = ["--problem", PROBLEM, "--steps", "60", "--budget-ms", "1000", "--budget-expansions", "5", "--seed", "1",
           "--agents", "100", "--action-model", "rotation", "--quiet"]


def rot_sig(log):
    return [log.get(k) for k in ("actionModel", "numTaskFinished", "numErrandFinished", "maxErrandTicks", "stallTicks",
                                 "guidance", "trafficFlow")]


@pytest.mark.parametrize("solver,rotation,flags", [
    ("pibt-rot", None, []),
    ("epibt", None, []),
    ("wppl", None, []),
    ("rtlacam", None, []),  # a cell solver under action_model="rotation": the rotation executor
    ("pibt-rot", dict(back_last=False, guidance_costs=[1, 5, 2], pocket_exit=False),
     ["--no-rot-back-last", "--guidance-costs", "1,5,2", "--no-rot-pocket-exit"]),
    ("epibt", dict(guidance="none", traffic_flow=False, depth=4, lns_rounds=0, revisit=1, priority="age",
                   pocket_exit=False, leavers_first=False),
     ["--guidance", "none", "--traffic-flow", "off", "--epibt-depth", "4", "--epibt-lns", "0", "--epibt-revisit", "1",
      "--epibt-priority", "age", "--no-epibt-pocket-exit", "--no-epibt-leavers-first"]),
    ("wppl", dict(back_last=False, guidance="arrows", pocket_exit=False, window=5, neighbourhood=2),
     ["--no-rot-back-last", "--guidance", "arrows", "--no-rot-pocket-exit", "--wppl-window", "5",
      "--wppl-neighbourhood", "2"]),
])
def test_lifelong_rotation_solver_equals_the_app_with_the_same_options(solver, rotation, flags):
    app = os.path.join(ROOT, "build", "apps", "rtlacam-lifelong")
    if not os.path.exists(app):
        pytest.skip("rtlacam-lifelong not built in build/")
    extra = dict(action_model="rotation") if solver == "rtlacam" else {}
    log = rtlacam.lifelong(PROBLEM, solver=solver, rotation=rotation, **ROT_ARGS, **extra)
    ref = json.loads(subprocess.run([app, "--solver", solver] + ROT_CLI + flags, capture_output=True, text=True,
                                    check=True).stdout)
    assert rot_sig(log) == rot_sig(ref)
    assert log["actionModel"] == "MAPF_T" and log["numPlannerErrors"] == 0 and log["numErrandFinished"] > 0
    if rotation:  # the options make another run than the defaults
        assert rot_sig(log) != rot_sig(rtlacam.lifelong(PROBLEM, solver=solver, **ROT_ARGS))


def test_lifelong_every_rotation_key_reaches_its_solver():
    # Each key a solver reads, set away from its default, changes that solver's run.
    keys = {"pibt-rot": dict(back_last=False, guidance="none", guidance_costs=[1, 5, 2], pocket_exit=False),
            "epibt": dict(guidance="none", guidance_costs=[1, 5, 2], traffic_flow=False, depth=4, lns_rounds=0,
                          priority="age", pocket_exit=False, leavers_first=False),
            "wppl": dict(back_last=False, guidance="arrows", pocket_exit=False, window=5, neighbourhood=2)}
    for solver, each in keys.items():
        base = rtlacam.lifelong(PROBLEM, solver=solver, **ROT_ARGS)["events"]
        assert rtlacam.lifelong(PROBLEM, solver=solver, rotation={}, **ROT_ARGS)["events"] == base
        for k, v in each.items():
            assert rtlacam.lifelong(PROBLEM, solver=solver, rotation={k: v}, **ROT_ARGS)["events"] != base, (solver, k)
    # epibt's revisit limits its priority pass (its LNS rounds keep the paper's 10): without LNS.
    no_lns = rtlacam.lifelong(PROBLEM, solver="epibt", rotation=dict(lns_rounds=0), **ROT_ARGS)["events"]
    assert rtlacam.lifelong(PROBLEM, solver="epibt", rotation=dict(lns_rounds=0, revisit=1), **ROT_ARGS)["events"] != no_lns


def test_lifelong_rotation_bad_input_is_one_line_naming_the_key():
    bad = [
        (dict(solver="epibt", rotation=dict(window=5)), "rotation.window: only with solver wppl, not epibt"),
        (dict(solver="pibt-rot", rotation=dict(revisit=10)), "rotation.revisit: only with solver epibt, not pibt-rot"),
        (dict(solver="epibt", rotation=dict(back_last=False)), "rotation.back_last: only with solver pibt-rot or wppl"),
        (dict(solver="rtlacam", rotation=dict(depth=4)), "rotation: only with a rotation solver .* not rtlacam"),
        (dict(solver="epibt", rotation=dict(dpeth=4)), "rotation: unknown key 'dpeth'"),
        (dict(solver="epibt", rotation="depth=4"), "rotation: expected a dict"),
        (dict(solver="epibt", rotation=dict(depth="4")), "rotation.depth: expected an integer"),
        (dict(solver="epibt", rotation=dict(depth=True)), "rotation.depth: expected an integer"),
        (dict(solver="epibt", rotation=dict(traffic_flow=1)), "rotation.traffic_flow: expected True or False"),
        (dict(solver="epibt", rotation=dict(priority=1)), "rotation.priority: expected a string"),
        (dict(solver="epibt", rotation=dict(depth=7)), r"rotation.depth: must be in 3\.\.5, got 7"),
        (dict(solver="epibt", rotation=dict(revisit=0)), r"rotation.revisit: must be in 1\.\.1000000, got 0"),
        (dict(solver="wppl", rotation=dict(window=2**70)), "rotation.window: .* is out of range"),
        (dict(solver="epibt", rotation=dict(priority="fifo")), "rotation.priority: must be distance or age"),
        (dict(solver="pibt-rot", rotation=dict(guidance="map.guidance")), "rotation.guidance: must be none or arrows"),
        (dict(solver="pibt-rot", rotation=dict(guidance_costs=[1, 0, 1])),
         r"rotation.guidance_costs\[1\]: must be in 1\.\.60, got 0"),
        (dict(solver="pibt-rot", rotation=dict(guidance_costs=[1, 3])), r"rotation.guidance_costs: expected \[along"),
        (dict(solver="wppl", rotation=dict(guidance_costs=[1, 3, 1])),
         "rotation.guidance_costs: only with guidance 'arrows'"),
        (dict(solver="epibt", action_model="grid4"), "action_model 'grid4': solver epibt plans rotation actions"),
        (dict(solver="rtlacam", action_model="hex"), "action_model: must be 'grid4' or 'rotation', not 'hex'"),
    ]
    for kw, msg in bad:
        with pytest.raises(rtlacam.InputError, match=msg) as e:
            rtlacam.lifelong(PROBLEM, steps=5, agents=5, **kw)
        assert isinstance(e.value, ValueError) and "\n" not in str(e.value), kw


# Values the app's options refuse: parking=[-3] corrupted the heap (double free), the
# others ran silently (agents=-1 as the whole team, NaN as the budget).
def test_lifelong_bad_values_raise():
    for kw, what in ((dict(parking=[-3]), "parking: cell -3 is not a vertex"),
                     (dict(parking=[10 ** 6]), "parking: cell 1000000 is not a vertex"),
                     (dict(budget_ms=float("nan")), "budget_ms"), (dict(budget_ms=-1), "budget_ms"),
                     (dict(agents=-1), "agents"), (dict(steps=-5), "steps"), (dict(pool_size=-1), "pool_size"),
                     (dict(pool_size=2 ** 31 - 1), "pool_size: must be at most 10000000")):
        args = dict(steps=5, budget_ms=1, agents=5)
        args.update(kw)
        with pytest.raises(ValueError, match=what):
            rtlacam.lifelong(PROBLEM, **args)


def test_lifelong_log_says_whether_the_agents_could_progress():
    log = rtlacam.lifelong(PROBLEM, steps=10, budget_ms=1, agents=5)
    assert log["unreachableGoals"] == 0 and log["unsolvableEpoch"] is False


def test_lifelong_highways_are_the_clis(tmp_path):
    # rtlacam-lifelong --highways P from Python: the same run as the app's, and another run
    # than with them off (a map with 1-wide aisles: warehouse-10-20-10-2-1).
    app = os.path.join(ROOT, "build", "apps", "rtlacam-lifelong")
    if not os.path.exists(app):
        pytest.skip("rtlacam-lifelong not built in build/")
    m = os.path.join(DATA, "planner", "warehouse-10-20-10-2-1.map")
    rows = open(m).read().split("\n")[4:]
    free = [y * len(rows[0]) + x for y, r in enumerate(rows) for x, c in enumerate(r) if c == "."]
    (tmp_path / "a.agents").write_text("60\n" + "".join(f"{free[(i * 90) % len(free)]}\n" for i in range(60)))
    tasks = free[5::37]
    (tmp_path / "t.tasks").write_text(f"{len(tasks)}\n" + "".join(f"{v}\n" for v in tasks))
    prob = tmp_path / "hw.json"
    prob.write_text(json.dumps({"mapFile": m, "agentFile": str(tmp_path / "a.agents"), "taskFile": str(tmp_path / "t.tasks"),
                                "teamSize": 60, "numTasksReveal": 1, "taskAssignmentStrategy": "roundrobin"}))
    args = dict(solver="rtlacam", steps=120, budget_ms=1000, budget_expansions=30, seed=2)
    on = rtlacam.lifelong(str(prob), highways=1, **args)
    off = rtlacam.lifelong(str(prob), **args)
    assert on["highways"] == 1 and "highways" not in off
    assert on["numPlannerErrors"] == 0 and off["numPlannerErrors"] == 0
    out = subprocess.run([app, "--problem", str(prob), "--solver", "rtlacam", "--steps", "120", "--budget-ms", "1000",
                          "--budget-expansions", "30", "--seed", "2", "--highways", "1", "--quiet", "--out",
                          str(tmp_path / "app.json")], capture_output=True, text=True, check=True)
    ref = json.load(open(tmp_path / "app.json"))
    assert on["highways"] == ref["highways"] == 1
    assert (on["numTaskFinished"], on["numErrandFinished"]) == (ref["numTaskFinished"], ref["numErrandFinished"])
    assert on["events"] != off["events"]
    with pytest.raises(ValueError, match="highways needs solver rtlacam or naive"):
        rtlacam.lifelong(str(prob), solver="pibt", highways=1, steps=5)
