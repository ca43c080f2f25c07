# Sourced by the sweep scripts (paper_fig2.sh, paper_fig3.sh): resumable parallel sweeps.
#
# Every run has a key (the first word of its line in the list of all runs); results carry
# it as "run_key". The script defines run_one (one run, appending to $RESULTS under
# $RESULTS.lock) and exports its variables, including COUNTER, RESULTS and ERRORS.

# pending_runs ALL RESULTS TODO: writes to TODO the lines of ALL whose key has no result
# yet and sets TOTAL, PENDING and SKIPPED.
pending_runs() {
  local all=$1 results=$2 todo=$3 done_file
  done_file="$(dirname "$todo")/.runs.done"
  TOTAL=$(wc -l <"$all")
  grep -o '"run_key":"[^"]*"' "$results" 2>/dev/null | sed 's/^"run_key":"//; s/"$//' | sort -u >"$done_file" || true
  awk -v donefile="$done_file" \
    'BEGIN { while ((getline l < donefile) > 0) done[l] = 1 } !($1 in done)' "$all" >"$todo"
  PENDING=$(wc -l <"$todo")
  SKIPPED=$((TOTAL - PENDING))
}

# count_done: one more run finished (runs are parallel); prints how many are done.
count_done() {
  { flock 9; local d=$(( $(cat "$COUNTER") + 1 )); echo "$d" >"$COUNTER"; echo "$d"; } 9>>"$RESULTS.lock"
}

# run_pending NAME ALL TODO JOBS: runs TODO's lines through run_one, JOBS at a time, then
# removes the bookkeeping files and reports (NAME labels the output).
run_pending() {
  local name=$1 all=$2 todo=$3 jobs=$4 start end
  echo "$SKIPPED" >"$COUNTER"
  export -f run_one count_done
  start=$(date +%s)
  if [[ $PENDING -gt 0 ]]; then
    xargs -P "$jobs" -L 1 bash -c 'run_one "$@"' _ <"$todo"
  fi
  end=$(date +%s)
  rm -f "$COUNTER" "$all" "$todo" "$(dirname "$todo")/.runs.done" "$RESULTS.lock"
  echo "$name sweep: done in $((end - start)) s; results in $RESULTS"
  if [[ -s "$ERRORS" ]]; then
    echo "$name sweep: WARNING: $(wc -l <"$ERRORS") crashed runs logged in $ERRORS (rerun the script to retry them)"
  fi
}
