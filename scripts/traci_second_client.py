#!/usr/bin/env python3
"""A second TraCI client on a SUMO the controller drives (sumo --num-clients 2): stops from
outside the controller, and what happens after the controller has gone.

It joins SUMO at TraCI order --order (the controller is 1: rtlacam-sumo --port P --order 1)
and steps with it. Until the controller is gone it may hold AGVs: --stop-share of them
(at least one), each after a pause of 3-15 s, brakes at --decel and is held at 0 for
--stop-s seconds, again and again -- a person, a pallet or a lost wheel the controller is not
told about (its Driver sees the speed SUMO reports and commands its own again afterwards).
Once the file --detached exists (written by whoever ran the controller, after it returned;
it may hold the SUMO time the controller detached at, else the time it is seen) it steps on
--after-s seconds of SUMO time more with no client driving, then writes a JSON report
(--report) and closes, which ends SUMO:
  agvs, stopped (ids held), steps_held, collisions (steps with colliding AGVs) and their
  ids, max_speed / max_accel / max_decel between consecutive steps (SUMO's speeds, what fcd
  writes), detach_t, check_t (detach_t + after_s), present_at_detach, present_at_check,
  moving_at_check (AGVs with a speed > 0 then), max_speed_at_check, max_speed_after_check
  (any step from check_t on), gone_after_detach (AGVs in the net at detach_t, not at the end).
Needs SUMO's Python tools (SUMO_HOME/tools: traci).
"""
import argparse
import json
import math
import os
import random
import sys
import time

sys.path.append(os.path.join(os.environ.get("SUMO_HOME", "/usr/share/sumo"), "tools"))
import traci  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--port", type=int, required=True)
    ap.add_argument("--order", type=int, default=2)
    ap.add_argument("--prefix", default="agv", help="ids of the AGVs")
    ap.add_argument("--stop-share", type=float, default=0.0, help="share of the AGVs stopped from outside (0: none)")
    ap.add_argument("--stop-s", type=float, nargs=2, default=[1.0, 5.0], help="length of a stop, min max")
    ap.add_argument("--decel", type=float, default=1.0, help="braking of a stopped AGV (its vType's decel)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--detached", required=True, help="file that appears once the controller has gone")
    ap.add_argument("--after-s", type=float, default=5.0)
    ap.add_argument("--max-s", type=float, default=3600.0, help="SUMO time past which it only waits for --detached")
    ap.add_argument("--report", required=True)
    a = ap.parse_args()

    traci.init(port=a.port, numRetries=30, label="second")
    traci.setOrder(a.order)
    rng = random.Random(a.seed)
    dt = None
    windows = {}  # AGV -> [(from, to)] s
    prev = {}     # AGV -> speed at the last step
    r = {"agvs": 0, "stopped": [], "steps_held": 0, "collisions": 0, "colliding": [], "max_speed": 0.0,
         "max_accel": 0.0, "max_decel": 0.0}
    detach_t = check_t = None
    last_seen = {}  # AGV -> SUMO time it was last in the net
    history = []    # (t, fastest AGV): the check covers every step from check_t on
    while True:
        if detach_t is None and os.path.exists(a.detached):
            text = open(a.detached).read().strip()
            detach_t = float(text) if text else traci.simulation.getTime()
            check_t = detach_t + a.after_s
        t = traci.simulation.getTime()
        if check_t is not None and t >= check_t - 1e-9:
            break
        if check_t is None and t >= a.max_s:
            time.sleep(0.02)  # the controller has long gone: wait for the file, SUMO stands still
            continue
        traci.simulationStep()
        t = traci.simulation.getTime()
        if dt is None:
            dt = traci.simulation.getDeltaT()
        ids = [v for v in traci.vehicle.getIDList() if v.startswith(a.prefix)]
        if not windows and ids and a.stop_share > 0:
            agvs = sorted(ids, key=lambda s: (len(s), s))
            r["agvs"] = len(agvs)
            chosen = rng.sample(agvs, max(1, int(round(a.stop_share * len(agvs)))))
            r["stopped"] = sorted(chosen, key=lambda s: (len(s), s))
            for v in chosen:
                w, s = [], t + rng.uniform(3, 15)
                while s < a.max_s:
                    length = rng.uniform(a.stop_s[0], a.stop_s[1])
                    w.append((s, s + length))
                    s += length + rng.uniform(3, 15)
                windows[v] = w
        r["agvs"] = max(r["agvs"], len(ids))
        col = [v for v in traci.simulation.getCollidingVehiclesIDList() if v.startswith(a.prefix)]
        if col:
            r["collisions"] += 1
            r["colliding"] = sorted(set(r["colliding"]) | set(col))
        speed = {}
        for v in ids:
            s = traci.vehicle.getSpeed(v)
            speed[v] = s
            r["max_speed"] = max(r["max_speed"], s)
            if v in prev:
                r["max_accel"] = max(r["max_accel"], (s - prev[v]) / dt)
                r["max_decel"] = max(r["max_decel"], (prev[v] - s) / dt)
        prev = speed
        for v in ids:
            last_seen[v] = t
        history.append((t, max(speed.values(), default=0.0)))
        if detach_t is None:
            for v, w in windows.items():
                if v in speed and any(lo <= t < hi for lo, hi in w):
                    traci.vehicle.setSpeed(v, max(0.0, speed[v] - a.decel * dt))
                    r["steps_held"] += 1
    ids = [v for v in traci.vehicle.getIDList() if v.startswith(a.prefix)]
    speeds = {v: traci.vehicle.getSpeed(v) for v in ids}
    # (SUMO may have stepped past detach_t before the file appeared: nobody drives then.)
    present_at_detach = {v for v, ts in last_seen.items() if ts >= detach_t - 1e-9}
    r.update({"detach_t": detach_t, "check_t": traci.simulation.getTime(), "present_at_detach": len(present_at_detach),
              "present_at_check": len(ids), "moving_at_check": sum(1 for s in speeds.values() if s > 0),
              "max_speed_at_check": max(speeds.values(), default=0.0),
              "max_speed_after_check": max((v for ts, v in history if ts >= check_t - 1e-9), default=0.0),
              "gone_after_detach": sorted(present_at_detach - set(ids))})
    traci.close()
    with open(a.report, "w") as f:
        json.dump(r, f, indent=1)


if __name__ == "__main__":
    main()
