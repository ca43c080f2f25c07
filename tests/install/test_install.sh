#!/usr/bin/env bash
# Installs the build tree to a temporary prefix, then configures, builds and runs a tiny
# consumer project with find_package(rtlacam): the exported targets, the config file, the
# installed headers and apps. Usage: test_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log"
for f in lib/cmake/rtlacam/rtlacam-config.cmake lib/cmake/rtlacam/rtlacam-config-version.cmake \
         include/planner/lacam/rt_lacam.hpp include/tasks/lifelong_runner.hpp bin/rtlacam-bench bin/rtlacam-lifelong; do
  [[ -e "$tmp/prefix/$f" ]] || { echo "test_install: $f not installed" >&2; exit 1; }
done
"$tmp/prefix/bin/rtlacam-bench" --version | grep -q '^rtlacam-bench [0-9]' \
  || { echo "test_install: installed rtlacam-bench --version is wrong" >&2; exit 1; }
# The Python package, when the bindings were built: importable from the prefix.
if [[ -d "$build/python/rtlacam" ]]; then
  # A temporary prefix is on no python's path: the install must say where it put the
  # package and which PYTHONPATH to set (a prefix python3 searches needs none).
  pydir=$(sed -n 's/.*rtlacam: Python package in \(.*\), which .* does not search: export PYTHONPATH=.*/\1/p' "$tmp/install.log")
  [[ -n "$pydir" && "$pydir" == "$tmp/prefix/lib/python3."*/site-packages ]] \
    || { echo "test_install: no 'export PYTHONPATH=' hint for the Python package" >&2; cat "$tmp/install.log" >&2; exit 1; }
  v=$(PYTHONPATH="$pydir" /usr/bin/python3 -c "import rtlacam; print(rtlacam.__version__)") \
    || { echo "test_install: the installed rtlacam Python package does not import" >&2; exit 1; }
  [[ "$v" == "$("$tmp/prefix/bin/rtlacam-bench" --version | cut -d' ' -f2)" ]] \
    || { echo "test_install: Python package version $v differs from the apps'" >&2; exit 1; }
fi
cmake -S "$src/tests/install/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_BUILD_TYPE=Release >"$tmp/configure.log" || { cat "$tmp/configure.log" >&2; exit 1; }
cmake --build "$tmp/consumer" >"$tmp/build.log" 2>&1 || { cat "$tmp/build.log" >&2; exit 1; }
out=$("$tmp/consumer/consumer" "$src/tests/data/planner/random-32-32-20.map" \
      "$src/tests/data/planner/random-32-32-20-random-1.scen" 20 "$src/policy/models/random-32-32-20.bin")
echo "$out"
[[ "$out" == solved=1* ]] || { echo "test_install: consumer did not solve" >&2; exit 1; }
