# Sourced by the sweep scripts (paper_fig2.sh, paper_fig3.sh): resumable parallel sweeps.
#
# Every run has a key (the first word of its line in the list of all runs); results carry
# it as "run_key". The script defines run_one (one run, usually through bench_record) and
# exports its variables, including BENCH, COUNTER, RESULTS and ERRORS.

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

# bench_record FIELDS ARGS...: one "$BENCH ARGS..." run. Its JSON line, with FIELDS (e.g.
# '"run_key":"k","scen_k":1') put first, is appended to $RESULTS; a crash is logged in
# $ERRORS with the command and its stderr. Sets MSG to a short outcome for the progress line.
bench_record() {
  local fields=$1 out err rc=0 line
  shift
  err=$(mktemp)
  out=$("$BENCH" "$@" 2>"$err") || rc=$?
  line=$(printf '%s\n' "$out" | grep -m1 '^{' || true)
  # 0 solved, 4 unsolved (a limit first), 3 invalid plan (flagged below): all results.
  if [[ ( $rc -eq 0 || $rc -eq 3 || $rc -eq 4 ) && -n "$line" ]]; then
    line="{$fields,${line#\{}"
    { flock 9; printf '%s\n' "$line" >>"$RESULTS"; } 9>>"$RESULTS.lock"
    MSG=$(printf '%s' "$line" | sed -n 's/.*"solved":\([a-z]*\).*"total_planning_ms":\([0-9.e+-]*\).*/solved=\1 t=\2ms/p')
    [[ "$line" == *'"valid":false'* ]] && MSG="$MSG INVALID PLAN"
  else
    MSG="CRASH rc=$rc (see $ERRORS)"
    { flock 9; printf 'rc=%s %s %s :: %s\n' "$rc" "$BENCH" "$*" "$(tr '\n' ' ' <"$err" | cut -c1-500)" >>"$ERRORS"; } 9>>"$RESULTS.lock"
  fi
  rm -f "$err"
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
  export -f run_one count_done bench_record
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
