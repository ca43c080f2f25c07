"""The planner from Python: maps, scenarios, every solver's search/next/commit, validator."""
import os
import subprocess
import sys

import pytest
import rtlacam

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "data")


def test_version_matches_the_apps():
    out = subprocess.run([sys.executable, "-m", "rtlacam", "--version"], capture_output=True, text=True, check=True)
    assert out.stdout == f"rtlacam {rtlacam.__version__}\n"
    assert rtlacam.__version__.count(".") == 2


def test_solvers_come_from_the_planner_factory():
    assert rtlacam.SOLVERS == ["pibt", "lacam", "rtlacam", "naive", "cspibt", "pibt-rot", "epibt", "wppl"]


def test_load_map_and_scen(grid, scen):
    assert (grid.width, grid.height) == (32, 32)
    assert len(grid) == 819  # free cells of random-32-32-20
    ins = rtlacam.load_scen(scen, grid, 10)
    assert ins.num_agents == 10 and len(ins.starts) == len(ins.goals) == 10
    v = ins.starts[0]
    x, y = grid.xy(v)
    assert grid.at(x, y) == v
    for u in grid.neighbors(v):
        assert grid.adjacent(u, v)
    assert ins.soc_lower_bound(grid) > 0


def test_bad_input_is_a_value_error_naming_the_file(tmp_path, grid):
    bad = tmp_path / "bad.map"
    bad.write_text("type octile\nheight 2\nwidth 2\nmap\n..\n.\n")
    with pytest.raises(ValueError, match="bad.map:6"):
        rtlacam.load_map(str(bad))
    with pytest.raises(rtlacam.InputError, match="cannot open"):
        rtlacam.load_map(str(tmp_path / "nope.map"))
    with pytest.raises(ValueError, match="unknown solver"):
        rtlacam.make_planner("magic", grid, [0], [0])
    with pytest.raises(ValueError, match="cspibt needs a policy"):
        rtlacam.make_planner("cspibt", grid, [0], [0])
    with pytest.raises(ValueError, match="not a real-time planner"):
        rtlacam.make_planner("lacam", grid, [0], [0])
    with pytest.raises(ValueError, match="out of range"):
        rtlacam.make_planner("rtlacam", grid, [len(grid)], [0])


# The rotation solvers (pibt-rot, epibt, wppl) come from the same factory; a turn keeps the
# cell, so the validator sees waits and moves only. They are not complete: 10 agents.
@pytest.mark.parametrize("solver,agents", [("rtlacam", 30), ("naive", 30), ("pibt", 30),
                                           ("pibt-rot", 10), ("epibt", 10), ("wppl", 10)])
def test_search_next_commit_reaches_the_goals_with_valid_moves(grid, scen, solver, agents):
    ins = rtlacam.load_scen(scen, grid, agents)
    p = rtlacam.make_planner(solver, grid, ins.starts, ins.goals, seed=1)
    assert p.name == solver and p.current == ins.starts and p.goals == ins.goals
    v = rtlacam.Validator(grid, ins.starts, ins.goals)
    for _ in range(2000):
        if p.at_goal:
            break
        p.search(expansions=5)
        assert v.step(p.next()), v.error
        p.commit()
    assert p.at_goal and v.ok
    assert p.current == ins.goals
    assert v.sum_of_costs >= ins.soc_lower_bound(grid)


def test_make_planner_takes_the_rotation_options(grid, scen):
    # rotation= (the SUMO YAML's planner.rotation keys) reaches each rotation solver; unset keys
    # keep the planners' own defaults (no guidance, no traffic flow), as before rotation=.
    ins = rtlacam.load_scen(scen, grid, 30)

    def moves(solver, rotation=None):
        p = rtlacam.make_planner(solver, grid, ins.starts, ins.goals, seed=1, rotation=rotation)
        v = rtlacam.Validator(grid, ins.starts, ins.goals)
        out = []
        for _ in range(40):
            p.search(expansions=5)
            assert v.step(p.next()), v.error
            out.append(p.next())
            p.commit()
        return out

    for solver, key in (("pibt-rot", dict(guidance="arrows")), ("epibt", dict(depth=5)), ("wppl", dict(window=3))):
        plain = moves(solver)
        assert moves(solver, {}) == plain and moves(solver, dict(guidance="none")) == plain, solver
        assert moves(solver, key) != plain, (solver, key)
    with pytest.raises(rtlacam.InputError, match="rotation.window: only with solver wppl, not epibt"):
        rtlacam.make_planner("epibt", grid, ins.starts, ins.goals, rotation=dict(window=5))
    with pytest.raises(ValueError, match="rotation: only with a rotation solver .* not rtlacam"):
        rtlacam.make_planner("rtlacam", grid, ins.starts, ins.goals, rotation={})


def test_set_goals_starts_a_new_search_from_where_the_agents_are(grid, scen):
    ins = rtlacam.load_scen(scen, grid, 10)
    p = rtlacam.make_planner("rtlacam", grid, ins.starts, ins.goals)
    while not p.at_goal:
        p.step(expansions=10)
        p.commit()
    p.set_goals(ins.starts)  # and back again
    assert not p.at_goal and p.goals == ins.starts
    while not p.at_goal:
        p.step(expansions=10)
        p.commit()
    assert p.current == ins.starts


@pytest.mark.parametrize("solver", ["rtlacam", "naive", "pibt"])
def test_an_immobile_agent_is_never_moved_and_all_finish_once_it_is_free(grid, scen, solver):
    ins = rtlacam.load_scen(scen, grid, 20)
    p = rtlacam.make_planner(solver, grid, ins.starts, ins.goals, seed=1)
    with pytest.raises(ValueError, match="agent 20 out of range"):
        p.set_immobile(20)
    p.set_immobile(0)
    v = rtlacam.Validator(grid, ins.starts, ins.goals)
    for _ in range(100):
        p.search(expansions=5)
        assert p.next()[0] == ins.starts[0]
        assert v.step(p.next()), v.error
        p.commit()
    assert not p.at_goal
    if solver == "rtlacam":  # complete again once it is free
        p.set_immobile(0, False)
        for _ in range(3000):
            if p.at_goal:
                break
            p.search(expansions=5)
            assert v.step(p.next()), v.error
            p.commit()
        assert p.current == ins.goals


def test_validator_catches_conflicts_and_bad_moves(grid, scen):
    a = rtlacam.load_scen(scen, grid, 1).starts[0]
    n = grid.neighbors(a)[0]
    starts, goals = [a, n], [n, a]
    v = rtlacam.Validator(grid, starts, goals)
    assert not v.step([a, a]) and "vertex conflict" in v.error
    assert not v.step(starts), "the sequence stays invalid after a violation"
    v = rtlacam.Validator(grid, starts, goals)
    assert not v.step([n, a]) and "swap conflict" in v.error
    far = next(u for u in range(len(grid)) if u not in (a, n) and not grid.adjacent(a, u))
    v = rtlacam.Validator(grid, starts, goals)
    assert not v.step([far, n]) and "not adjacent" in v.error
    v = rtlacam.Validator(grid, starts, goals)
    assert v.step(starts) and v.ok and v.steps == 1
    assert rtlacam.validate_plan(grid, starts, goals, [starts], require_goals=False) == ""
    assert "not the goals" in rtlacam.validate_plan(grid, starts, goals, [starts], require_goals=True)
    assert "swap conflict" in rtlacam.validate_plan(grid, starts, goals, [starts, goals], require_goals=True)


@pytest.mark.parametrize("solver", ["lacam", "rtlacam", "naive", "pibt"])
def test_run_is_the_benchs_loop(grid, scen, solver):
    ins = rtlacam.load_scen(scen, grid, 50)
    r = rtlacam.run(solver, grid, ins, time_ms=None, expansions=20)
    assert r["solved"] and r["valid"], r["validation_error"]
    assert r["soc"] >= ins.soc_lower_bound(grid)
    assert r["plan"][0] == ins.starts and r["plan"][-1] == ins.goals
    assert rtlacam.validate_plan(grid, ins.starts, ins.goals, r["plan"]) == ""


def test_step_limit_is_reported_unsolved(grid, scen):
    ins = rtlacam.load_scen(scen, grid, 50)
    r = rtlacam.run("pibt", grid, ins, max_steps=2)
    assert not r["solved"] and r["step_limit"] and r["valid"]


def test_learned_policy_drives_cspibt(grid, scen, weights):
    ins = rtlacam.load_scen(scen, grid, 20)
    pref = rtlacam.PolicyPreference(grid, rtlacam.load_policy(weights), ins.goals)
    p = rtlacam.make_planner("cspibt", grid, ins.starts, ins.goals, policy=pref)
    del pref  # the planner keeps it alive
    v = rtlacam.Validator(grid, ins.starts, ins.goals)
    for _ in range(300):
        p.search(expansions=1)
        assert v.step(p.next()), v.error
        p.commit()
    assert v.ok and v.steps == 300


def test_graph_outlives_its_python_name(scen):
    import gc
    import os
    from conftest import DATA
    g = rtlacam.load_map(os.path.join(DATA, "planner", "random-32-32-20.map"))
    ins = rtlacam.load_scen(scen, g, 5)
    p = rtlacam.make_planner("rtlacam", g, ins.starts, ins.goals)
    del g
    gc.collect()
    p.search(expansions=1000)
    assert p.at_goal or p.next() is not None


def test_rtlacam_is_rt_lacam_star_as_on_the_cli_and_refine_false_is_the_papers_planner(grid, scen):
    # The CLI's names: rtlacam-bench --solver rtlacam refines (RT-LaCAM*), --no-refine is the
    # paper's RT-LaCAM, whose search is LaCAM's very own (same expansions, same explored set).
    ins = rtlacam.load_scen(scen, grid, 30)
    lacam = rtlacam.run("lacam", grid, ins, time_ms=None, expansions=20)
    paper = rtlacam.run("rtlacam", grid, ins, time_ms=None, expansions=20, refine=False)
    star = rtlacam.run("rtlacam", grid, ins, time_ms=None, expansions=20)
    assert paper["solved"] and star["solved"] and paper["valid"] and star["valid"]
    assert (paper["expansions"], paper["explored"]) == (lacam["expansions"], lacam["explored"])
    assert star["expansions"] > lacam["expansions"]  # it went on refining after the first solution
    # Under objective="loss" LaCAM*'s followed path never gets costlier in its cost, the sum of
    # loss; the default, objective="soc", lowers the standard SOC instead (rtlacam-bench --objective)
    loss = rtlacam.run("rtlacam", grid, ins, time_ms=None, expansions=20, objective="loss")
    assert loss["solved"] and loss["valid"]
    assert loss["sum_of_loss"] <= paper["sum_of_loss"] <= paper["soc"]
    with pytest.raises(ValueError, match="objective"):
        rtlacam.run("rtlacam", grid, ins, time_ms=None, expansions=20, objective="makespan")
    with pytest.raises(ValueError, match="objective"):
        rtlacam.make_planner("rtlacam", grid, ins.starts, ins.goals, objective="makespan")


def test_iter_refine_is_the_clis_iter_refine(grid, scen):
    # rtlacam-bench --iter-refine: RT-LaCAM* refines by iterative refinement (lacam3's refiner)
    # instead of LNS; deterministic under an expansion budget, so the executed plan differs.
    ins = rtlacam.load_scen(scen, grid, 60)
    lns = rtlacam.run("rtlacam", grid, ins, time_ms=None, expansions=20)
    it = rtlacam.run("rtlacam", grid, ins, time_ms=None, expansions=20, iter_refine=True)
    assert lns["solved"] and it["solved"] and lns["valid"] and it["valid"]
    assert it["soc"] != lns["soc"] or it["expansions"] != lns["expansions"]
    p = rtlacam.make_planner("rtlacam", grid, ins.starts, ins.goals, iter_refine=True)
    p.search(expansions=1000)
    assert p.at_goal or p.next() is not None


def test_lacam_anytime_ms_refines_before_executing_as_on_the_cli(grid, scen):
    # rtlacam-bench --solver lacam --refine --anytime-ms T: LaCAM* refines until T ms, then
    # executes, by iterative refinement unless iter_refine=False. Never costlier than the first
    # solution (executed with anytime_ms=0).
    ins = rtlacam.load_scen(scen, grid, 60)
    first = rtlacam.run("lacam", grid, ins, time_ms=None)
    star = rtlacam.run("lacam", grid, ins, time_ms=None, anytime_ms=300)
    lns = rtlacam.run("lacam", grid, ins, time_ms=None, anytime_ms=300, iter_refine=False)
    for r in (first, star, lns):
        assert r["solved"] and r["valid"]
    assert star["total_planning_ms"] >= 250 and first["total_planning_ms"] < 250
    assert star["soc"] <= first["soc"] and lns["soc"] <= first["soc"]
    with pytest.raises(ValueError, match="anytime_ms"):
        rtlacam.run("lacam", grid, ins, anytime_ms=-1)


def test_highways_are_the_clis_highways():
    # rtlacam-bench --highways P: RT-LaCAM*'s PIBT ranks a move against a 1-wide aisle's grain as
    # 1 + P (default 1 for RT-LaCAM*, 0 for the paper's RT-LaCAM and LaCAM). On a warehouse the
    # executed plan is cheaper with them; deterministic under an expansion budget.
    import rtlacam
    g = rtlacam.load_map(os.path.join(DATA, "planner", "warehouse-10-20-10-2-1.map"))
    ins = rtlacam.load_scen(os.path.join(DATA, "planner", "warehouse-10-20-10-2-1-random-2-first200.scen"), g, 200)
    on = rtlacam.run("rtlacam", g, ins, time_ms=None, expansions=4)
    off = rtlacam.run("rtlacam", g, ins, time_ms=None, expansions=4, highways=0)
    one = rtlacam.run("rtlacam", g, ins, time_ms=None, expansions=4, highways=1)
    for r in (on, off, one):
        assert r["solved"] and r["valid"]
    assert on["soc"] == one["soc"] and on["soc"] < off["soc"]
    paper = rtlacam.run("rtlacam", g, ins, time_ms=None, expansions=4, refine=False)
    paper_off = rtlacam.run("rtlacam", g, ins, time_ms=None, expansions=4, refine=False, highways=0)
    assert paper["soc"] == paper_off["soc"]
    with pytest.raises(ValueError, match="highways"):
        rtlacam.run("rtlacam", g, ins, highways=-1)
    p = rtlacam.make_planner("rtlacam", g, ins.starts, ins.goals, highways=2)
    p.search(expansions=100)
    assert p.at_goal or p.next() is not None


def test_highway_arcs_are_moves_against_an_aisles_grain(grid):
    # rtlacam.highway_arcs: what scripts/highways_map.py draws. Each is a move w -> u along a row
    # or a column, charged the penalty; a random map without 1-wide runs of 3 cells has none.
    g = rtlacam.load_map(os.path.join(DATA, "planner", "warehouse-10-20-10-2-1.map"))
    arcs = rtlacam.highway_arcs(g, 2)
    assert len(arcs) > 1000
    for w, u, c in arcs:
        assert c == 2 and g.adjacent(w, u)
        (xw, yw), (xu, yu) = g.xy(w), g.xy(u)
        assert abs(xw - xu) + abs(yw - yu) == 1
    against = {(w, u) for w, u, _ in arcs}
    assert all((u, w) not in against for w, u in against)  # one way of each aisle move is cheap
    assert rtlacam.highway_arcs(grid) == []
    assert rtlacam.highway_arcs(g, 0) == []
    with pytest.raises(ValueError, match="min_run"):
        rtlacam.highway_arcs(g, 1, 0)


# Bad arguments raise, never crash: search() converted its budget after releasing the GIL
# (segfault on expansions=-1 or time_ms="x"), and the vertices handed to set_goals, the
# Validator and PolicyPreference index tables unchecked.
def test_bad_budgets_raise_instead_of_crashing(grid, scen):
    ins = rtlacam.load_scen(scen, grid, 5)
    for solver in ("rtlacam", "pibt"):
        p = rtlacam.make_planner(solver, grid, ins.starts, ins.goals)
        for bad in (-1, float("nan"), float("inf")):
            with pytest.raises(ValueError, match="time_ms"):
                p.search(time_ms=bad)
        with pytest.raises(TypeError, match="time_ms"):
            p.search(time_ms="x")
        for bad in (-1, 2 ** 64):
            with pytest.raises(ValueError, match="expansions"):
                p.search(expansions=bad)
        with pytest.raises(TypeError, match="expansions"):
            p.search(expansions=1.5)
        with pytest.raises(ValueError, match="expansions"):
            p.step(expansions=-1)
        assert p.search(time_ms=0, expansions=0) in ("searching", "solved")
    for kw, what in ((dict(time_ms=-1), "time_ms"), (dict(time_ms=float("nan")), "time_ms"),
                     (dict(timeout_ms=-1), "timeout_ms"), (dict(timeout_ms=float("nan")), "timeout_ms"),
                     (dict(max_steps=-1), "max_steps"), (dict(anytime_ms=float("nan")), "anytime_ms")):
        with pytest.raises(ValueError, match=what):
            rtlacam.run("rtlacam", grid, ins, **kw)


def test_goals_and_starts_off_the_graph_raise(grid, scen, weights):
    ins = rtlacam.load_scen(scen, grid, 2)
    p = rtlacam.make_planner("rtlacam", grid, ins.starts, ins.goals)
    with pytest.raises(ValueError, match="vertex 100000000 is out of range"):
        p.set_goals([100000000, ins.goals[1]])
    with pytest.raises(ValueError, match="1 vertices for 2 agents"):
        p.set_goals([ins.goals[0]])
    assert p.goals == ins.goals  # unchanged
    p.set_goals(ins.starts)
    assert p.goals == ins.starts
    for bad in ([-5, ins.starts[1]], [ins.starts[0], 100000000]):
        with pytest.raises(ValueError, match="starts: agent .* is out of range"):
            rtlacam.Validator(grid, bad, ins.goals)
        with pytest.raises(ValueError, match="starts: agent .* is out of range"):
            rtlacam.validate_plan(grid, bad, ins.goals, [bad, ins.goals])
    with pytest.raises(ValueError, match="goals: 1 vertices for 2 agents"):
        rtlacam.Validator(grid, ins.starts, ins.goals[:1])
    v = rtlacam.Validator(grid, ins.starts, ins.goals)
    with pytest.raises(ValueError, match="goals: agent 0's vertex -1"):
        v.set_goals([-1, 0])
    with pytest.raises(ValueError, match="goals: agent 0's vertex 99999 is out of range"):
        rtlacam.PolicyPreference(grid, rtlacam.load_policy(weights), [99999])


# load_scen refuses two agents on one start (or goal); make_planner planned from the conflict.
def test_make_planner_refuses_shared_starts_and_goals(grid, scen):
    a, b, c = rtlacam.load_scen(scen, grid, 3).starts
    for solver in ("rtlacam", "pibt", "naive"):
        with pytest.raises(ValueError, match="starts: agents 0 and 1 share vertex"):
            rtlacam.make_planner(solver, grid, [a, a], [b, c])
        with pytest.raises(ValueError, match="goals: agents 0 and 1 share vertex"):
            rtlacam.make_planner(solver, grid, [a, b], [c, c])
