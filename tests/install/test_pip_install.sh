#!/usr/bin/env bash
# `pip install . --no-build-isolation` (pyproject.toml + setup.py) into a fresh venv that
# sees Debian's setuptools, wheel and pybind11 (--system-site-packages), reusing BUILD_DIR
# through RTLACAM_BUILD_DIR so the module is not compiled twice; then, from another
# folder, the installed package imports and solves a small instance.
# Usage: test_pip_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$tmp/venv"
RTLACAM_BUILD_DIR="$build" "$tmp/venv/bin/python" -m pip install --no-build-isolation --no-deps --no-index -q "$src" \
  >"$tmp/pip.log" 2>&1 || { cat "$tmp/pip.log" >&2; exit 1; }
cd "$tmp"
"$tmp/venv/bin/python" - "$src" "$tmp/venv" <<'PY'
import os, sys
import rtlacam
src, venv = sys.argv[1], sys.argv[2]
assert os.path.realpath(rtlacam.__file__).startswith(os.path.realpath(venv)), rtlacam.__file__
g = rtlacam.load_map(os.path.join(src, "tests/data/planner/random-32-32-20.map"))
ins = rtlacam.load_scen(os.path.join(src, "tests/data/planner/random-32-32-20-random-1.scen"), g, 20)
p = rtlacam.make_planner("rtlacam", g, ins.starts, ins.goals)
steps = 0
while not p.at_goal and steps < 1000:
    p.search(expansions=50)
    p.next()
    p.commit()
    steps += 1
assert p.at_goal, "not solved"
print("pip-installed rtlacam", rtlacam.__version__, "from", os.path.dirname(rtlacam.__file__), "solved in", steps, "steps")
PY
