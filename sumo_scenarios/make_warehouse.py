#!/usr/bin/env python3
"""Writes the plain-XML inputs (.nod.xml, .edg.xml, .add.xml) of the warehouse scenarios.

A warehouse here: vertical picking aisles between shelf blocks, joined by horizontal
cross aisles; dead-end stub aisles outside the bottom cross aisle end at pick-up stations
and stubs above the top one at drop stations; parking spots are parkingAreas in the
outer aisles. Every aisle is a pair of opposite one-way single-lane edges (see
gridify/README.md). Node coordinates are whole metres, so with cell_length 1 every
aisle length is a multiple of the cell.

Also writes `huge` (the 1000-AGV benchmark warehouse, scripts/bench_sumo.sh) and
`bottleneck`: a single corridor with dead-end sidings, where two groups of AGVs must pass
each other (config/bottleneck.yaml: naive replanning livelocks there, RT-LaCAM finishes).

Also writes `small_oneway`: `small` with one-way picking aisles in alternate directions.

Also writes one member of a warehouse family (aisles x shelf rows as parameters) anywhere:
scripts/bench_scale.py uses it for its robots-vs-latency table.

Usage: make_warehouse.py  (writes small.*, small_charging.*, small_oneway.*, large.*, large_oneway.*, large_charging.*, large_slow.*, huge.*, bottleneck.* here; then run ./build.sh)
       make_warehouse.py --family AISLES ROWS --name NAME --out DIR  (writes DIR/NAME.{nod,edg,add}.xml)
"""
import argparse
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = HERE  # where write() puts the files (--out)


def warehouse(name, columns, pitch, cross_ys, stub, pick_cols, drop_cols, park, one_way=False,
              charge_below=(), charge_above=(), slow_cols=(), slow_speed=0.25):
    """one_way: the picking aisles are single one-way edges, alternately up (even columns)
    and down (odd columns); cross aisles and station stubs stay two-way (a stub is a dead
    end, which a one-way edge could not leave). charge_below / charge_above: columns with a
    dead-end charger stub below the bottom / above the top cross aisle, a chargingStation
    at its end (a charging AGV there blocks no aisle). slow_cols: picking aisles whose lanes
    have speed slow_speed (m/s) instead of 1.0."""
    nodes, edges = {}, []
    top = cross_ys[-1]
    for c in range(columns):
        for r, y in enumerate(cross_ys):
            nodes[f"c{c}r{r}"] = (c * pitch, y)
    def aisle(a, b):
        edges.append((f"{a}_{b}", a, b))
        edges.append((f"{b}_{a}", b, a))
    for r in range(len(cross_ys)):            # cross aisles
        for c in range(columns - 1):
            aisle(f"c{c}r{r}", f"c{c + 1}r{r}")
    for c in range(columns):                  # picking aisles between shelf blocks
        for r in range(len(cross_ys) - 1):
            a, b = f"c{c}r{r}", f"c{c}r{r + 1}"
            if not one_way:
                aisle(a, b)
            elif c % 2 == 0:
                edges.append((f"{a}_{b}", a, b))
            else:
                edges.append((f"{b}_{a}", b, a))
    stations = []
    for c in pick_cols:                       # pick-up stations below the bottom cross aisle
        nodes[f"pick{c}"] = (c * pitch, -stub)
        aisle(f"c{c}r0", f"pick{c}")
        stations.append(("busStop", f"pickup{c}", f"c{c}r0_pick{c}_0", stub, "pickup"))
    last = len(cross_ys) - 1
    for c in drop_cols:                       # drop stations above the top cross aisle
        nodes[f"drop{c}"] = (c * pitch, top + stub)
        aisle(f"c{c}r{last}", f"drop{c}")
        stations.append(("busStop", f"drop{c}", f"c{c}r{last}_drop{c}_0", stub, "drop"))
    for c in charge_below:                    # charger stubs (fleet.battery)
        nodes[f"chgB{c}"] = (c * pitch, -stub)
        aisle(f"c{c}r0", f"chgB{c}")
        stations.append(("chargingStation", f"charger_b{c}", f"c{c}r0_chgB{c}_0", stub, "charging"))
    for c in charge_above:
        nodes[f"chgT{c}"] = (c * pitch, top + stub)
        aisle(f"c{c}r{last}", f"chgT{c}")
        stations.append(("chargingStation", f"charger_t{c}", f"c{c}r{last}_chgT{c}_0", stub, "charging"))
    for k, (c, r, pos) in enumerate(park):    # parking spots inside the outer picking aisles
        lane = f"c{c}r{r}_c{c}r{r + 1}_0" if not one_way or c % 2 == 0 else f"c{c}r{r + 1}_c{c}r{r}_0"
        stations.append(("parkingArea", f"park{k}", lane, pos, "parking"))

    # A lone one-way edge is drawn on the centreline and netconvert 1.15 then computes lane
    # lengths from the junction shapes (7.94 m for an 8 m aisle, 3.47 m for a 4 m one):
    # fixing every length to the node distance keeps lane position == cell offset.
    slow = {f"c{c}r{r}_c{c}r{r + 1}" for c in slow_cols for r in range(len(cross_ys) - 1)}
    slow |= {f"c{c}r{r + 1}_c{c}r{r}" for c in slow_cols for r in range(len(cross_ys) - 1)}
    speeds = {e: slow_speed for e, _, _ in edges if e in slow}
    write(name, nodes, edges, stations, fixed_lengths=one_way, speeds=speeds)
    return stations


def write(name, nodes, edges, stations, fixed_lengths=False, speeds=None):
    with open(os.path.join(OUT, f"{name}.nod.xml"), "w") as f:
        f.write("<nodes>\n")
        for n, (x, y) in nodes.items():
            f.write(f'    <node id="{n}" x="{x:.2f}" y="{y:.2f}" type="unregulated"/>\n')
        f.write("</nodes>\n")
    with open(os.path.join(OUT, f"{name}.edg.xml"), "w") as f:
        f.write("<edges>\n")
        for e, a, b in edges:
            (xa, ya), (xb, yb) = nodes[a], nodes[b]
            length = f' length="{((xb - xa) ** 2 + (yb - ya) ** 2) ** 0.5:.2f}"' if fixed_lengths else ""
            speed = (speeds or {}).get(e, 1.0)
            f.write(f'    <edge id="{e}" from="{a}" to="{b}" numLanes="1" speed="{speed}" width="1.0"{length}/>\n')
        f.write("</edges>\n")
    write_additional(name, stations)


def write_additional(name, stations):
    with open(os.path.join(OUT, f"{name}.add.xml"), "w") as f:
        f.write("<additional>\n")
        for elem, sid, lane, pos, kind in stations:
            # A stop covers [pos - 0.5, pos] so its middle snaps to the cell at `pos`.
            extra = ' roadsideCapacity="1"' if elem == "parkingArea" else ""
            if elem == "chargingStation":  # 7.2 kW at SUMO's default efficiency: 1.9 Wh per second
                extra = ' power="7200" efficiency="0.95"'
            f.write(f'    <{elem} id="{sid}" lane="{lane}" startPos="{pos - 0.5:.2f}" endPos="{pos:.2f}"{extra}>\n')
            f.write(f'        <param key="kind" value="{kind}"/>\n')
            f.write(f"    </{elem}>\n")
        f.write("</additional>\n")


def corridor(name, length, sidings, siding_length, bays):
    """A corridor `west` -> `east` (x = 0 .. length) with dead-end sidings going north at
    the x in `sidings`; busStops w1..w<bays> / e1..e<bays> tag the corridor cells 1..bays
    metres from either end (the ends themselves are the junctions `west` and `east`)."""
    nodes = {"west": (0, 0), "east": (length, 0)}
    chain = ["west"] + [f"j{x}" for x in sidings] + ["east"]
    for x in sidings:
        nodes[f"j{x}"] = (x, 0)
        nodes[f"siding{x}"] = (x, siding_length)
    edges = []
    def aisle(a, b):
        edges.append((f"{a}_{b}", a, b))
        edges.append((f"{b}_{a}", b, a))
    for a, b in zip(chain, chain[1:]):
        aisle(a, b)
    for x in sidings:
        aisle(f"j{x}", f"siding{x}")
    stations = []
    for k in range(1, bays + 1):
        stations.append(("busStop", f"w{k}", f"west_{chain[1]}_0", k, "bay"))
        stations.append(("busStop", f"e{k}", f"east_{chain[-2]}_0", k, "bay"))
    write(name, nodes, edges, stations)


def family(name, aisles, rows):
    """One member of the family: `aisles` picking aisles 10 m long at a 4 m pitch in `rows`
    shelf rows (cross aisles every 10 m), a pick-up stub of 3 m under every even aisle and a
    drop stub over every odd one, no parking (the huge warehouse is family(48, 7))."""
    if aisles < 2 or rows < 1:
        raise SystemExit(f"make_warehouse.py: --family needs AISLES >= 2 and ROWS >= 1, not {aisles} {rows}")
    return warehouse(name, columns=aisles, pitch=4, cross_ys=list(range(0, 10 * rows + 1, 10)), stub=3,
                     pick_cols=list(range(0, aisles, 2)), drop_cols=list(range(1, aisles, 2)), park=[])


def shipped():
    # Small: 4 picking aisles 8 m long between 3 m shelf blocks, 2 pick-up and 2 drop stations.
    warehouse("small", columns=4, pitch=4, cross_ys=[0, 8], stub=2,
              pick_cols=[1, 2], drop_cols=[0, 3], park=[(0, 0, 3)])
    # Small with chargers (issue 24, config/small_charging_lifelong.yaml): `small` plus four
    # dead-end charger stubs, below the outer picking aisles and above the inner ones.
    warehouse("small_charging", columns=4, pitch=4, cross_ys=[0, 8], stub=2,
              pick_cols=[1, 2], drop_cols=[0, 3], park=[(0, 0, 3)], charge_below=[0, 3], charge_above=[1, 2])
    # Small with one-way picking aisles (alternately up and down; issue 24): the same layout,
    # stations and parking spot (config/small_oneway.yaml, small_oneway_lifelong.yaml).
    warehouse("small_oneway", columns=4, pitch=4, cross_ys=[0, 8], stub=2,
              pick_cols=[1, 2], drop_cols=[0, 3], park=[(0, 0, 3)], one_way=True)
    # Large: 16 picking aisles, two shelf rows (cross aisles at y = 0, 12, 24),
    # 8 pick-up and 8 drop stations, 4 parking spots.
    large = warehouse("large", columns=16, pitch=4, cross_ys=[0, 12, 24], stub=3,
                      pick_cols=list(range(0, 16, 2)), drop_cols=list(range(1, 16, 2)),
                      park=[(0, 0, 4), (0, 1, 4), (15, 0, 8), (15, 1, 8)])
    # Large with one-way picking aisles (alternately up and down; issue 24): the same layout,
    # stations and parking spots (config/large_oneway_lifelong.yaml; scripts/bench_rules.py
    # compares it with `large`).
    warehouse("large_oneway", columns=16, pitch=4, cross_ys=[0, 12, 24], stub=3,
              pick_cols=list(range(0, 16, 2)), drop_cols=list(range(1, 16, 2)),
              park=[(0, 0, 4), (0, 1, 4), (15, 0, 8), (15, 1, 8)], one_way=True)
    # Large with chargers (issue 24, config/large_charging_lifelong.yaml): `large` plus 16
    # dead-end charger stubs, below the odd picking aisles (no pick-up stub there) and above
    # the even ones (no drop stub there): 30 Wh per tick for 200 AGVs.
    warehouse("large_charging", columns=16, pitch=4, cross_ys=[0, 12, 24], stub=3,
              pick_cols=list(range(0, 16, 2)), drop_cols=list(range(1, 16, 2)),
              park=[(0, 0, 4), (0, 1, 4), (15, 0, 8), (15, 1, 8)],
              charge_below=list(range(1, 16, 2)), charge_above=list(range(0, 16, 2)))
    # Large with slow picking aisles (issue 24, lane speeds; config/large_slow_lifelong.yaml):
    # `large` with every fourth picking aisle at 0.25 m/s.
    warehouse("large_slow", columns=16, pitch=4, cross_ys=[0, 12, 24], stub=3,
              pick_cols=list(range(0, 16, 2)), drop_cols=list(range(1, 16, 2)),
              park=[(0, 0, 4), (0, 1, 4), (15, 0, 8), (15, 1, 8)], slow_cols=[1, 5, 9, 13])
    # Large with a parking lane (issue 24, config/large_warehouse_parking.yaml): the same net and
    # stations, and parking spots on every other cell of both outer picking aisles (20 spots:
    # a spot between two parked AGVs stays free, so one can leave or pass).
    write_additional("large_parking", [st for st in large if st[0] != "parkingArea"] +
                     [("parkingArea", f"lot{c}_{r}_{pos}", f"c{c}r{r}_c{c}r{r + 1}_0", pos, "parking")
                      for c in (0, 15) for r in (0, 1) for pos in (2, 4, 6, 8, 10)])
    # Huge (benchmark, 1000 AGVs): 48 picking aisles 10 m long in 7 shelf rows (cross aisles
    # every 10 m), 24 pick-up and 24 drop stations: about 4600 cells.
    family("huge", 48, 7)
    # Bottleneck: a 16 m corridor with three 2 m sidings (x = 4, 8, 12); 4 AGVs at each end
    # swap ends (config/bottleneck.yaml).
    corridor("bottleneck", length=16, sidings=[4, 8, 12], siding_length=2, bays=3)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--family", nargs=2, type=int, metavar=("AISLES", "ROWS"),
                    help="write one member of the warehouse family instead of the shipped scenarios")
    ap.add_argument("--name", default="family", help="--family: file name stem")
    ap.add_argument("--out", default=HERE, help="--family: output folder")
    a = ap.parse_args()
    if a.family:
        OUT = a.out
        os.makedirs(OUT, exist_ok=True)
        family(a.name, *a.family)
    else:
        shipped()
