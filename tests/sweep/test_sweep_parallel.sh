#!/usr/bin/env bash
# scripts/sweep.py through GNU parallel: every row gets a result file (unsolved ones too),
# a failing row an error file and a non-zero sweep; --joblog/--resume and the result files
# make a second call run only what failed; collect keeps CSV order; a bad CSV is one line
# naming file:line with exit 2. Usage: test_sweep_parallel.sh BENCH_BIN SOURCE_DIR
set -euo pipefail
bench=$1 src=$2
command -v parallel >/dev/null || { echo "GNU parallel not installed: skipped"; exit 77; }
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
die() { echo "test_sweep_parallel: $*" >&2; exit 1; }
py=/usr/bin/python3
sweep="$src/scripts/sweep.py"
M=tests/data/planner/random-32-32-20.map
S=tests/data/planner/random-32-32-20-random-1.scen
cat >"$t/s.csv" <<CSV
key,map,scen,agents,solver,budget_expansions,cutoff_ms,max_steps,no_swap
b,$M,$S,20,rtlacam,10,,100000,false
a,$M,$S,20,naive,10,,100000,true
limit,$M,$S,60,pibt,10,,2,
bad,$M,/nope.scen,20,rtlacam,10,,100000,
CSV
rc=0
$py "$sweep" parallel "$t/s.csv" "$t/out" --app "$bench" -j 2 >"$t/log" 2>&1 || rc=$?
[[ $rc -ne 0 ]] || die "a failed row must fail the sweep"
[[ "$(ls "$t/out/results")" == "$(printf 'a.json\nb.json\nlimit.json')" ]] || die "results: $(ls "$t/out/results")"
grep -q '/nope.scen: cannot open' "$t/out/errors/bad.txt" || die "error file: $(cat "$t/out/errors/bad.txt")"
grep -q '"run_key": "limit".*"solved": false' "$t/out/results/limit.json" || die "unsolved result: $(cat "$t/out/results/limit.json")"
grep -q '"swap": false' "$t/out/results/a.json" || die "a 'true' cell is a flag (--no-swap)"
grep -q '"swap": true' "$t/out/results/b.json" || die "a 'false' cell is left out"
[[ $(grep -c . "$t/out/joblog") -eq 5 ]] || die "joblog: $(cat "$t/out/joblog")"
# Resume after fixing the bad row: only it runs again (sweep.py run skips rows with a
# result; GNU parallel --resume-failed would too).
sed -i 's|/nope.scen|'"$S"'|' "$t/s.csv"
$py "$sweep" parallel "$t/s.csv" "$t/out" --app "$bench" -j 2 >"$t/log2" 2>&1 || die "resume failed: $(cat "$t/log2")"
[[ -f "$t/out/results/bad.json" && ! -e "$t/out/errors/bad.txt" ]] || die "the fixed row did not rerun"
[[ $(grep -c . "$t/out/joblog") -eq 6 ]] || die "finished rows ran again: $(cat "$t/out/joblog")"
# Multi-host form: a --sshloginfile (here only ":", this machine) gives the same results.
echo ":" >"$t/hosts"
$py "$sweep" parallel "$t/s.csv" "$t/out-ssh" --app "$bench" --sshloginfile "$t/hosts" >"$t/log3" 2>&1 \
  || die "--sshloginfile: $(cat "$t/log3")"
for k in a b limit bad; do
  [[ "$(grep -o '"soc": [0-9]*' "$t/out/results/$k.json")" == "$(grep -o '"soc": [0-9]*' "$t/out-ssh/results/$k.json")" ]] \
    || die "--sshloginfile: $k differs"
done
[[ "$($py "$sweep" status "$t/s.csv" "$t/out")" == "4 done, 0 failed, 0 pending of 4" ]] || die "status"
[[ "$($py "$sweep" collect "$t/s.csv" "$t/out" | sed 's/.*"run_key": "\([^"]*\)".*/\1/' | tr '\n' ' ')" == "b a limit bad " ]] \
  || die "collect order"
# Bad sweep description: one line, file:line, exit 2.
printf 'key,map\nx,a\nx,b\n' >"$t/dup.csv"
rc=0
err=$($py "$sweep" parallel "$t/dup.csv" "$t/o2" --app "$bench" 2>&1) || rc=$?
[[ $rc -eq 2 && "$err" == "sweep.py: $t/dup.csv:3: duplicate key 'x'" ]] || die "bad CSV: rc=$rc $err"
echo "test_sweep_parallel: OK"
