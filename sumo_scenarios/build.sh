#!/bin/sh
# Rebuilds the scenarios (small, small_charging, small_oneway, large, large_oneway, large_charging, large_slow, huge warehouses; bottleneck corridor): plain XML -> .net.xml with SUMO 1.15 netconvert, then
# gridifies them (summary, SVG) if rtlacam-gridify is given as $1.
# The netconvert options make lane length == distance between node centres (no internal
# lanes, zero junction radius) and add turnarounds at every node, corners included.
set -e
# Both arguments are relative to the caller's folder, not this one: made absolute before the cd.
gridify_bin="" svg_dir=""
if [ -n "$1" ]; then case "$1" in /*) gridify_bin="$1" ;; *) gridify_bin="$PWD/$1" ;; esac; fi
if [ -n "$2" ]; then case "$2" in /*) svg_dir="$2" ;; *) svg_dir="$PWD/$2" ;; esac; fi
cd "$(dirname "$0")"
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
python3 make_warehouse.py
for s in small small_charging small_oneway large large_oneway large_charging large_slow huge bottleneck tree; do  # tree.nod/edg.xml: hand-written (issue 21: dead-end aisles only)
  netconvert -n $s.nod.xml -e $s.edg.xml -o $s.net.xml \
    --no-internal-links --no-turnarounds.geometry false \
    --default.junctions.radius 0 --junctions.corner-detail 0 --offset.disable-normalization
  if [ -n "$gridify_bin" ]; then mkdir -p "${svg_dir:-.}" && "$gridify_bin" $s.net.xml --additional $s.add.xml --svg "${svg_dir:-.}/$s.svg"; fi
done
