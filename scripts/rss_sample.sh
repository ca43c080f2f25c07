#!/bin/bash
# RSS of a run over time: starts `rtlacam-sumo CONFIG --out OUTDIR`, samples VmRSS (kB) and
# the tick of its last progress line every second into LOG ("unix-time tick rss-kB"),
# then "rc=N". docs/faults.md "Memory of long runs".
# Usage: scripts/rss_sample.sh BIN CONFIG OUTDIR LOG
bin=$1 cfg=$2 out=$3 log=$4
"$bin" "$cfg" --out "$out" >"$log.stdout" 2>"$log.stderr" &
pid=$!
: >"$log"
while kill -0 $pid 2>/dev/null; do
  rss=$(awk '/VmRSS/{print $2}' /proc/$pid/status 2>/dev/null)
  tick=$(grep -o 'tick [0-9][0-9]*' "$log.stderr" | tail -1 | cut -d' ' -f2)
  echo "$(date +%s) ${tick:-0} ${rss:-0}" >>"$log"
  sleep 1
done
wait $pid
echo "rc=$?" >>"$log"
