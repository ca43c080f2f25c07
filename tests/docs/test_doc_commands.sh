#!/usr/bin/env bash
# Docs that run: the short commands of README.md and the folder READMEs, each checked to
# appear verbatim in its document (edit one, edit the other) and run as written from a
# folder laid out like a fresh clone (the source folders linked, ./build -> BUILD_DIR),
# with the exit code the document gives. Usage: test_doc_commands.sh BUILD_DIR SOURCE_DIR
set -uo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for d in config data tests sumo_scenarios scripts policy tools; do ln -s "$src/$d" "$tmp/$d"; done
ln -s "$build" "$tmp/build"
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
fail=0
# DOC|EXIT|COMMAND (COMMAND as the document prints it, up to any trailing "# comment")
while IFS='|' read -r doc code cmd; do
  [[ -z "$doc" || "$doc" == \#* ]] && continue
  if ! grep -qF -- "$cmd" "$src/$doc"; then
    echo "doc commands: '$cmd' is no longer in $doc (update tests/docs/test_doc_commands.sh)" >&2
    fail=1
    continue
  fi
  (cd "$tmp" && eval "$cmd") >"$tmp/out.log" 2>&1
  rc=$?
  if [[ $rc -ne $code ]]; then
    echo "doc commands: $doc: '$cmd' exited $rc, the document says $code:" >&2
    tail -5 "$tmp/out.log" >&2
    fail=1
  else
    echo "ok ($rc): $doc: $cmd"
  fi
done <<'CMDS'
README.md|0|./build/apps/rtlacam-bench --map data/movingai/warehouse-10-20-10-2-1.map --scen data/movingai/warehouse-10-20-10-2-1-random-1.scen -N 400 --solver rtlacam --cutoff-ms 1
README.md|0|./build/apps/rtlacam-sumo config/small_warehouse_agv.yaml
controller/README.md|0|./build/apps/rtlacam-sumo config/small_warehouse.yaml
controller/README.md|0|./build/apps/rtlacam-sumo config/bottleneck.yaml
controller/README.md|4|./build/apps/rtlacam-sumo config/bottleneck.yaml --solver naive
controller/README.md|0|./build/apps/rtlacam-sumo config/small_rules.yaml
docs/rt_lacam_star.md|0|./build/apps/rtlacam-gridify sumo_scenarios/small.net.xml --additional sumo_scenarios/small.add.xml --map out/small.map
CMDS
# rtlacam-ggo --out/--log into folders that do not exist yet (tools/ggo/README.md's
# out/ggo/...), with a tiny search instead of the documented 45 minutes.
grep -qF -- "--out out/ggo/random-32-32-20_400.guidance --log out/ggo/i05.log" "$src/tools/ggo/README.md" || {
  echo "doc commands: tools/ggo/README.md no longer writes to out/ggo/" >&2; fail=1; }
if [[ -x "$build/tools/ggo/rtlacam-ggo" ]]; then
  (cd "$tmp" && build/tools/ggo/rtlacam-ggo --problem tests/data/tasks/lorr/2024/random.domain/RANDOM-01.json \
     --steps 20 --generations 1 --lambda 2 --out out/ggo/x.guidance --log out/ggo/x.log) >"$tmp/out.log" 2>&1
  rc=$?
  if [[ $rc -ne 0 || ! -s "$tmp/out/ggo/x.log" || ! -s "$tmp/out/ggo/x.guidance" ]]; then
    echo "doc commands: rtlacam-ggo into out/ggo/ exited $rc:" >&2; tail -5 "$tmp/out.log" >&2; fail=1
  else
    echo "ok (0): rtlacam-ggo --out out/ggo/... --log out/ggo/... (folders created)"
  fi
fi
exit $fail
