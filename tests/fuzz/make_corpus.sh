#!/usr/bin/env bash
# Seed corpora for the fuzz targets, from the repository's own test and benchmark files.
# Usage: tests/fuzz/make_corpus.sh [out_dir]   (default: build-fuzz/corpus)
# One directory per target; libFuzzer adds what it finds to the first corpus directory.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-$root/build-fuzz/corpus}
mkdir -p "$out"/{fuzz_movingai_map,fuzz_movingai_scen,fuzz_lorr_problem,fuzz_lorr_files,fuzz_policy_files,fuzz_net,fuzz_config}

cp -f "$root"/data/movingai/*.map "$out/fuzz_movingai_map/"
cp -f "$root"/tests/data/planner/*.scen "$root"/data/movingai/random-32-32-20-random-2[0-4].scen "$root"/data/movingai/room-32-32-4-random-1.scen "$out/fuzz_movingai_scen/"
printf 'type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n' > "$out/fuzz_movingai_map/small.map"
printf 'version 1\n0\tm.map\t32\t32\t0\t0\t1\t0\t1\n' > "$out/fuzz_movingai_scen/one.scen"

lorr=$root/tests/data/tasks/lorr
i=0
for y in 2023 2024; do
  for p in "$lorr"/$y/*/*.json; do
    cp -f "$p" "$out/fuzz_lorr_problem/problem$i.json"
    { cat "$p"; printf '\0'; cat "$lorr/$y/simulation_time.json"; } > "$out/fuzz_lorr_problem/with_time$i.json"
    i=$((i + 1))
  done
  for f in "$lorr"/$y/*/agents/* "$lorr"/$y/*/tasks/*; do head -c 2000 "$f" > "$out/fuzz_lorr_files/$y-$(basename "$f")"; done
done
printf '2\n0\n1\n' > "$out/fuzz_lorr_files/two.agents"
printf '# c\n2\n0,1,2\n3\n' > "$out/fuzz_lorr_files/two.tasks"

# Small valid weights and golden files (the trained model is 500 KB: too slow a seed).
python3 - "$out/fuzz_policy_files" <<'PY'
import struct, sys
d = sys.argv[1]
w = b"RTLPOLCY" + struct.pack("<7I", 1, 1, 4, 5, 1, 5, 36) + struct.pack("<180f", *([0.5] * 180)) + struct.pack("<5f", *range(5))
open(d + "/tiny.weights", "wb").write(w)
w2 = (b"RTLPOLCY" + struct.pack("<7I", 1, 1, 4, 5, 2, 3, 36) + struct.pack("<108f", *([0.25] * 108)) + struct.pack("<3f", 1, 2, 3)
      + struct.pack("<2I", 5, 3) + struct.pack("<15f", *([1.0] * 15)) + struct.pack("<5f", *range(5)))
open(d + "/two_layers.weights", "wb").write(w2)
g = b"RTLGOLDN" + struct.pack("<4I", 1, 2, 3, 5) + struct.pack("<6f", *range(6)) + struct.pack("<10f", *range(10))
open(d + "/tiny.golden", "wb").write(g)
PY

for f in "$root"/tests/data/gridify/*.net.xml "$root"/tests/data/gridify/not_a_net.xml; do cp -f "$f" "$out/fuzz_net/"; done
{ cat "$root/tests/data/gridify/tiny.net.xml"; printf '\0'; cat "$root/tests/data/gridify/tiny_stations.add.xml"; } > "$out/fuzz_net/tiny_with_stations.xml"
cp -f "$root/sumo_scenarios/small.net.xml" "$out/fuzz_net/"

for f in "$root"/config/*.yaml; do
  # The configs name ../sumo_scenarios/...; the target resolves paths against sumo_scenarios/.
  sed 's#\.\./sumo_scenarios/##' "$f" > "$out/fuzz_config/$(basename "$f")"
done
echo "seed corpora in $out"
