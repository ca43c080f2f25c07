#!/usr/bin/env python3
"""Reads a LoRR log the way PlanViz does and replays it the way LoRR checks it.

PlanViz (MAPF-Competition/PlanViz, script/run.py + plan_config.py) picks its reader by
`version` ("2024 LoRR" -> PlanConfig2024, otherwise PlanConfig2023) and then accesses the
fields below with these types; a missing field or a wrong type is what makes it crash
(KeyError, IndexError, assert). On top of that this script replays `actualPaths` from
`start` with PlanViz's state transitions and checks every step as LoRR's ActionModel does
(cells free and in bounds, no vertex or swap conflict) and every finished errand against
the robot's cell. Exit 0 when the log would load and replay cleanly; else one line per
problem on stderr and exit 1.

    check_lorr_log.py --map M.map --plan log.json
"""
import argparse
import json
import sys

DIRECTION = {"E": 0, "N": 1, "W": 2, "S": 3}  # PlanViz util.DIRECTION


def step_mapf_t(s, m):  # PlanViz util.state_transition
    r, c, o = s
    if m == "F":
        return [(r, c + 1, o), (r - 1, c, o), (r, c - 1, o), (r + 1, c, o)][o]
    if m == "R":
        return (r, c, (o + 3) % 4)
    if m == "C":
        return (r, c, (o + 1) % 4)
    if m in ("W", "T"):
        return s
    raise ValueError(f"invalid MAPF_T motion {m!r}")


def step_mapf(s, m):  # PlanViz util.state_transition_mapf
    r, c, o = s
    moves = {"U": (1, 0), "D": (-1, 0), "L": (0, -1), "R": (0, 1), "W": (0, 0), "T": (0, 0)}
    if m not in moves:
        raise ValueError(f"invalid MAPF motion {m!r}")
    return (r + moves[m][0], c + moves[m][1], o)


def load_map(path):
    with open(path) as f:
        lines = f.read().splitlines()
    h = int(lines[1].split()[1])
    w = int(lines[2].split()[1])
    grid = lines[4:4 + h]
    return h, w, [[ch in ".SE" for ch in row] for row in grid]


def need(cond, msg, errors):
    if not cond:
        errors.append(msg)
    return cond


def check(map_file, plan_file):
    errors = []
    h, w, free = load_map(map_file)
    with open(plan_file) as f:
        d = json.load(f)
    for k, t in [("teamSize", int), ("makespan", int), ("actionModel", str), ("start", list),
                 ("actualPaths", list), ("plannerPaths", list), ("errors", list), ("events", list),
                 ("tasks", list), ("plannerTimes", list), ("numTaskFinished", int)]:
        if not need(k in d and isinstance(d[k], t), f"field {k}: missing or not {t.__name__}", errors):
            return errors
    v2024 = d.get("version") in ("2024 LoRR", "2026 LoRR")
    n, T = d["teamSize"], d["makespan"]
    need(d["actionModel"] in ("MAPF", "MAPF_T"), f"actionModel {d['actionModel']!r} is neither MAPF nor MAPF_T", errors)
    step = step_mapf if d["actionModel"] == "MAPF" else step_mapf_t
    need(len(d["plannerTimes"]) == T and all(isinstance(x, (int, float)) for x in d["plannerTimes"]),
         "plannerTimes: not one number per step", errors)
    for k in ("start", "actualPaths", "plannerPaths"):
        need(len(d[k]) >= n, f"{k}: fewer than teamSize entries", errors)
    if errors:
        return errors
    # Replay.
    states = []
    for a in range(n):
        s = d["start"][a]
        if not need(len(s) == 3 and s[2] in DIRECTION, f"start[{a}] = {s!r}", errors):
            return errors
        states.append((int(s[0]), int(s[1]), DIRECTION[s[2]]))
    paths = []
    for a in range(n):
        for k in ("actualPaths", "plannerPaths"):
            need(isinstance(d[k][a], str), f"{k}[{a}] is not a string", errors)
        p = d["actualPaths"][a].split(",") if d["actualPaths"][a] else []
        need(len(p) == T, f"actualPaths[{a}]: {len(p)} actions for makespan {T}", errors)
        paths.append(p)
    if errors:
        return errors
    traj = [states]
    for t in range(T):
        nxt = [step(states[a], paths[a][t]) for a in range(n)]
        seen = {}
        for a in range(n):
            r, c, _ = nxt[a]
            if not (0 <= r < h and 0 <= c < w and free[r][c]):
                errors.append(f"step {t + 1}: agent {a} off the map or on an obstacle at {(r, c)}")
            cell = (r, c)
            if cell in seen:
                errors.append(f"step {t + 1}: vertex conflict of agents {seen[cell]} and {a} at {cell}")
            seen[cell] = a
        moved = {(states[a][:2], nxt[a][:2]): a for a in range(n) if states[a][:2] != nxt[a][:2]}
        for (u, v), a in moved.items():
            if (v, u) in moved:
                errors.append(f"step {t + 1}: swap conflict of agents {a} and {moved[(v, u)]}")
        if len(errors) > 20:
            return errors
        states = nxt
        traj.append(states)
    # Tasks and events, as PlanViz reads them.
    finished = 0
    if v2024:
        seq = {}
        for task in d["tasks"]:
            tid, rel, locs = task[0], task[1], task[2]
            need(isinstance(tid, int) and isinstance(rel, int) and isinstance(locs, list) and len(locs) % 2 == 0,
                 f"task {task!r}", errors)
            seq[tid] = [(locs[2 * i], locs[2 * i + 1]) for i in range(len(locs) // 2)]
        for e in d["events"]:
            if not need(len(e) == 4 and all(isinstance(x, int) for x in e), f"event {e!r}", errors):
                continue
            t, a, tid, nxt_errand = e
            need(tid in seq and 0 <= nxt_errand - 1 < len(seq.get(tid, [])), f"event {e!r}: no such task/errand (PlanViz KeyError)", errors)
            if tid in seq and 0 <= nxt_errand - 1 < len(seq[tid]):
                need(traj[t][a][:2] == seq[tid][nxt_errand - 1], f"event {e!r}: agent not on the errand cell", errors)
                finished += nxt_errand == len(seq[tid])
        for k in ("actualSchedule", "plannerSchedule"):
            if need(k in d and isinstance(d[k], list) and len(d[k]) >= n, f"{k}: missing or short", errors):
                for a, sched in enumerate(d[k][:n]):
                    for ele in filter(None, sched.split(",")):
                        t, tid = (int(x) for x in ele.split(":"))
                        need(tid == -1 or tid in seq, f"{k}[{a}]: task {tid} not in tasks (PlanViz assert)", errors)
    else:
        tasks = d["tasks"]
        for i, task in enumerate(tasks):
            need(len(task) == 3 and task[0] == i, f"tasks[{i}] = {task!r}: id must equal its index (PlanViz assert)", errors)
        need(len(d["events"]) >= n, "events: not one list per agent", errors)
        for a, evs in enumerate(d["events"][:n]):
            for e in evs:
                if not need(len(e) == 3 and e[2] in ("assigned", "finished") and isinstance(e[0], int) and isinstance(e[1], int),
                            f"events[{a}] {e!r}", errors):
                    continue
                tid, t = e[0], e[1]
                if need(0 <= tid < len(tasks), f"events[{a}] {e!r}: no such task", errors) and e[2] == "finished":
                    need(traj[t][a][:2] == (tasks[tid][1], tasks[tid][2]), f"events[{a}] {e!r}: agent not on the task cell", errors)
                    finished += 1
    need(finished == d["numTaskFinished"], f"{finished} finished tasks in events, numTaskFinished {d['numTaskFinished']}", errors)
    return errors


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", required=True)
    ap.add_argument("--plan", required=True)
    args = ap.parse_args()
    errors = check(args.map, args.plan)
    for e in errors[:20]:
        print(f"{args.plan}: {e}", file=sys.stderr)
    if not errors:
        print(f"{args.plan}: ok")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
