#!/usr/bin/env bash
# One fuzz campaign: tests/fuzz/run.sh <target> [seconds=240] [extra libFuzzer flags...]
# Needs build-fuzz (README.md) and the seed corpora (make_corpus.sh). New inputs go to
# build-fuzz/corpus/<target>, crashes to build-fuzz/artifacts/<target>/, the log to
# build-fuzz/logs/<target>.log. One fuzzing process, in-process (no -jobs/-workers:
# those fork a child that logs to fuzz-N.log in the working directory).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${RTLACAM_FUZZ_BUILD:-$root/build-fuzz}
t=${1:?target, e.g. fuzz_net}
secs=${2:-240}
shift $(($# < 2 ? $# : 2))
case $t in
  fuzz_movingai_*) dict=movingai ;;
  fuzz_lorr_*) dict=lorr ;;
  fuzz_net) dict=xml ;;
  fuzz_config) dict=yaml ;;
  *) dict= ;;
esac
mkdir -p "$build/artifacts/$t" "$build/logs" "$build/corpus/$t"
"$build/tests/fuzz/$t" "$build/corpus/$t" \
  ${dict:+-dict="$root/tests/fuzz/dict/$dict.dict"} \
  -max_total_time="$secs" -rss_limit_mb=2048 -timeout=10 \
  -artifact_prefix="$build/artifacts/$t/" -print_final_stats=1 "$@" > "$build/logs/$t.log" 2>&1 && rc=0 || rc=$?
grep -v -e '^#[0-9]' -e '^	NEW_FUNC' "$build/logs/$t.log" | tail -n 60
exit $rc
