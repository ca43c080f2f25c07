#!/usr/bin/env python3
"""Draw a grid map's highways (planner/highways.hpp, rtlacam-bench --highways): every 1-wide
corridor run that gets a grain, as arrows in the cheap direction; obstacles dark.

  scripts/highways_map.py ../shared/benchmarks/movingai/warehouse-10-20-10-2-1.map --out docs/highways.png
      [--min-run 3] [--crop X0 Y0 X1 Y1]

Needs the Python module (build/python on PYTHONPATH) and matplotlib.
"""
import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "build", "python"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("map")
    ap.add_argument("--out", required=True)
    ap.add_argument("--min-run", type=int, default=3)
    ap.add_argument("--crop", type=int, nargs=4, metavar=("X0", "Y0", "X1", "Y1"), help="cells shown (inclusive)")
    a = ap.parse_args()
    try:
        import rtlacam
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        sys.exit(f"highways_map: {e} (build the Python module; install matplotlib)")
    g = rtlacam.load_map(a.map)
    arcs = rtlacam.highway_arcs(g, 1, a.min_run)
    x0, y0, x1, y1 = a.crop or (0, 0, g.width - 1, g.height - 1)
    w, h = x1 - x0 + 1, y1 - y0 + 1
    fig, ax = plt.subplots(figsize=(max(4, w / 8), max(2, h / 8)))
    blocked = [[1.0 if g.at(x, y) < 0 else 0.0 for x in range(x0, x1 + 1)] for y in range(y0, y1 + 1)]
    ax.imshow(blocked, cmap="Greys", vmin=0, vmax=1.6, extent=(x0 - 0.5, x1 + 0.5, y1 + 0.5, y0 - 0.5))
    # A penalised arc w -> u runs against the grain: the grain points u -> w.
    for w_, u, _ in arcs:
        (xw, yw), (xu, yu) = g.xy(w_), g.xy(u)
        if not (x0 <= xw <= x1 and y0 <= yw <= y1):
            continue
        ax.annotate("", xy=(xw, yw), xytext=(xu, yu),
                    arrowprops=dict(arrowstyle="-|>", color="tab:blue", lw=0.6, mutation_scale=5))
    ax.set_title(f"{os.path.basename(a.map)}: highways (min run {a.min_run}), {len(arcs)} arcs against the grain",
                 fontsize=8)
    ax.set_xticks([])
    ax.set_yticks([])
    fig.tight_layout()
    fig.savefig(a.out, dpi=150)
    print(f"highways_map: wrote {a.out} ({len(arcs)} arcs against the grain)")


if __name__ == "__main__":
    main()
