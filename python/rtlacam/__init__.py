"""RT-LaCAM (Real-Time LaCAM; Liang, Veerapaneni, Harabor, Li, Likhachev, SoCS 2025) from Python.

    import rtlacam
    g = rtlacam.load_map("random-32-32-20.map")
    ins = rtlacam.load_scen("random-32-32-20-random-1.scen", g, 50)
    p = rtlacam.make_planner("rtlacam", g, ins.starts, ins.goals)
    v = rtlacam.Validator(g, ins.starts, ins.goals)
    while not p.at_goal:
        p.search(time_ms=1.0)        # think (wall clock and/or expansions=)
        assert v.step(p.next()), v.error
        p.commit()                   # the agents moved there

Configurations are lists of vertex ids. Bad input raises rtlacam.InputError (a
ValueError naming the file and line). See python/README.md.
"""
from ._rtlacam import (  # noqa: F401
    SOLVERS,
    __version__,
    Graph,
    Instance,
    InputError,
    Planner,
    Policy,
    PolicyPreference,
    Validator,
    highway_arcs,
    lifelong,
    load_map,
    load_policy,
    load_scen,
    make_planner,
    run,
    validate_plan,
)
