#!/bin/sh
# Rebuilds the gridify test fixtures with SUMO 1.15 (exact commands; outputs are committed,
# so the tests need no SUMO). The hand-written broken files (malformed*.net.xml, ...) are
# not generated.
set -e
cd "$(dirname "$0")"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
OPTS="--no-internal-links --no-turnarounds.geometry false --default.junctions.radius 0 --junctions.corner-detail 0 --offset.disable-normalization"
# oneway: a one-way dead end b->d (not strongly connected); oneway_loop: one-way rows
# (east below, west above) joined by two-way cross aisles.
for n in oneway oneway_loop notmultiple disconnected; do
  netconvert -n $n.nod.xml -e $n.edg.xml -o $n.net.xml $OPTS
done
# The same kind of net, but with SUMO's default internal links: gridify must refuse it.
netconvert -n internal.nod.xml -e internal.edg.xml -o internal.net.xml \
  --no-turnarounds.geometry false --default.junctions.radius 0 --junctions.corner-detail 0 --offset.disable-normalization
# A line a-b-c without any turnaround (--no-turnarounds): the dead ends a and c lose their
# links, b lacks the U-turns.
netconvert -n noturnarounds.nod.xml -e noturnarounds.edg.xml -o noturnarounds.net.xml \
  --no-internal-links --no-turnarounds --default.junctions.radius 0 --junctions.corner-detail 0 --offset.disable-normalization
netgenerate --grid --grid.x-number 4 --grid.y-number 3 --grid.length 5 \
  --default.lanenumber 1 --default.lanewidth 1.0 --default.speed 1.0 \
  --default-junction-type unregulated --no-internal-links \
  --default.junctions.radius 0 --junctions.corner-detail 0 --no-turnarounds.geometry false \
  -o grid4x3.net.xml
# Hand-written: tiny.net.xml (trimmed netconvert output of a 3 m aisle a-b) and its broken
# copies malformed / missing_length / nonnumeric / unknown_junction / not_a_net / empty,
# plus the station files *.add.xml.
