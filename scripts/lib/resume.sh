# Sourced by the sweep scripts: resumable sweeps. Every run has a key (the first word of
# its line in the list of all runs); results carry it as "run_key". pending_runs ALL
# RESULTS TODO writes to TODO the lines of ALL whose key has no result yet and sets
# TOTAL, PENDING and SKIPPED.
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
