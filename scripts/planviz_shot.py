#!/usr/bin/env python3
"""Opens a log in PlanViz, presses play, and saves a screenshot of the whole X screen.

PlanViz is not ours and is not in this repository: pass a checkout of
MAPF-Competition/PlanViz (--planviz DIR). Runs under a virtual display:

    xvfb-run -s "-screen 0 1600x1000x24" /usr/bin/python3 scripts/planviz_shot.py \
        --planviz PLANVIZ --map M.map --plan log.json --after-s 8 -o shot.png

Needs PlanViz's requirements (Debian: python3-tk python3-numpy python3-pandas
python3-matplotlib python3-pil python3-pil.imagetk python3-scipy python3-numba) and
ImageMagick's `import` for the screenshot.
"""
import argparse
import json
import os
import subprocess
import sys
import tkinter as tk

ap = argparse.ArgumentParser()
ap.add_argument("--planviz", required=True, help="PlanViz checkout (has script/run.py)")
ap.add_argument("--map", required=True)
ap.add_argument("--plan", required=True)
ap.add_argument("--after-s", type=float, default=8, help="seconds of playing before the screenshot")
ap.add_argument("-o", "--out", required=True)
args = ap.parse_args()
# PlanViz reads relative to its script/ folder (the chdir below): make ours absolute first.
for k in ("planviz", "map", "plan", "out"):
    setattr(args, k, os.path.abspath(getattr(args, k)))

sys.path.insert(0, os.path.join(args.planviz, "script"))
os.chdir(os.path.join(args.planviz, "script"))
from plan_config import PlanConfig2023, PlanConfig2024  # noqa: E402
from plan_viz import PlanViz2023, PlanViz2024  # noqa: E402

with open(args.plan) as f:
    version = json.load(f).get("version")
inf = float("inf")
if version in ("2024 LoRR", "2026 LoRR"):
    pcf = PlanConfig2024(args.map, args.plan, inf, 0, inf, 50000, None, None, None, version, event_limit=100)
    viz = PlanViz2024(pcf, True, True, False, False, False)
else:
    pcf = PlanConfig2023(args.map, args.plan, inf, 0, inf, None, None, None, [], "", [], "")
    viz = PlanViz2023(pcf, True, True, False, False, False)


def shoot():
    subprocess.run(["import", "-window", "root", args.out], check=True)
    print(f"{args.out}: t = {getattr(pcf, 'cur_tstep', '?')}")
    os._exit(0)


pcf.window.after(1500, viz.move_agents)  # the Play button
pcf.window.after(int(1500 + args.after_s * 1000), shoot)
tk.mainloop()
