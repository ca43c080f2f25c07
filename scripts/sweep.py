#!/usr/bin/env python3
"""Sweeps of rtlacam runs on an existing scheduler: GNU parallel (one machine or many) or Slurm.

A sweep is a CSV file, one run per row. Column `key` names the run (unique; it names the
result file); every other non-empty cell becomes an option of the app, `--COLUMN VALUE`
(underscores become dashes); a cell `true` is a bare flag (`--no-swap`), `false` is left out.

    key,map,scen,agents,solver,cutoff_ms,timeout_s
    r32-50-1-rtlacam,data/movingai/random-32-32-20.map,data/movingai/random-32-32-20-random-1.scen,50,rtlacam,1,5

Every run, whatever executes it, goes through `sweep.py run CSV OUT ROW`, which writes
OUT/results/KEY.json (the app's JSON line with "run_key" first, plus the row's cells the
app does not echo, e.g. "timeout_s") or, when the app fails
(exit 1 or 2, or no JSON), OUT/errors/KEY.txt; exit 0 (solved), 4 (unsolved / limit) and 3
(invalid plan: "valid":false in the result) are all results. So both back ends leave the
same files, a finished run is never redone, and `collect` joins them into one JSONL.

    sweep.py parallel CSV OUT [-j N] [--sshloginfile FILE]   # GNU parallel, --joblog/--resume-failed
    sweep.py slurm CSV OUT [--wait] [-- sbatch options]      # one job array, pending rows only
    sweep.py collect CSV OUT                                 # results in CSV order -> stdout
    sweep.py status CSV OUT                                  # done / failed / pending counts

Remote hosts (--sshloginfile) and Slurm nodes must see this checkout, the app and OUT at
the same paths (a shared file system, as on a cluster).
"""
import argparse
import csv
import json
import os
import shlex
import shutil
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
SELF = os.path.abspath(__file__)
DEFAULT_APP = os.path.join(ROOT, "build", "apps", "rtlacam-bench")
RESULT_CODES = (0, 3, 4)  # ok, invalid plan, unsolved / limit reached (README "Exit codes")


def fail(msg):
    print(f"sweep.py: {msg}", file=sys.stderr)
    sys.exit(2)


def read_runs(path):
    """The rows of the sweep CSV as (key, [args], {column: cell}) in file order; errors name file:line."""
    try:
        f = open(path, newline="")
    except OSError as e:
        fail(f"{path}: cannot open ({e.strerror})")
    with f:
        rows = list(csv.reader(f))
    if not rows or "key" not in rows[0]:
        fail(f"{path}:1: the header needs a 'key' column")
    header = [h.strip() for h in rows[0]]
    runs, seen = [], set()
    for line, row in enumerate(rows[1:], start=2):
        if not row or (len(row) == 1 and not row[0].strip()) or row[0].startswith("#"):
            continue
        if len(row) != len(header):
            fail(f"{path}:{line}: {len(row)} cells, the header has {len(header)}")
        cells = dict(zip(header, (c.strip() for c in row)))
        key = cells.pop("key")
        if not key or "/" in key or key.startswith("."):
            fail(f"{path}:{line}: bad key '{key}' (it names a file)")
        if key in seen:
            fail(f"{path}:{line}: duplicate key '{key}'")
        seen.add(key)
        args = []
        for col, val in cells.items():
            opt = "--" + col.replace("_", "-")
            if val == "" or val.lower() == "false":
                continue
            args += [opt] if val.lower() == "true" else [opt, val]
        runs.append((key, args, cells))
    if not runs:
        fail(f"{path}: no runs")
    return runs


def result_path(out, key):
    return os.path.join(out, "results", key + ".json")


def pending_rows(runs, out):
    """1-based row numbers of the runs without a result file."""
    return [i + 1 for i, (key, *_) in enumerate(runs) if not os.path.exists(result_path(out, key))]


def cmd_run(a):
    runs = read_runs(a.csv)
    if not 1 <= a.row <= len(runs):
        fail(f"row {a.row} out of range 1..{len(runs)}")
    key, args, cells = runs[a.row - 1]
    if os.path.exists(result_path(a.out, key)):
        return 0
    cmd = [a.app, *args, "--json"]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    line = next((l for l in p.stdout.splitlines() if l.startswith("{")), None)
    if p.returncode in RESULT_CODES and line:
        rec = {"run_key": key, **json.loads(line)}
        for col, val in cells.items():  # the row's settings the app does not echo (e.g. timeout_s)
            rec.setdefault(col, val)
        os.makedirs(os.path.join(a.out, "results"), exist_ok=True)
        tmp = result_path(a.out, key) + f".tmp{os.getpid()}"
        with open(tmp, "w") as f:
            f.write(json.dumps(rec) + "\n")
        os.replace(tmp, result_path(a.out, key))  # atomic: a result file is whole or absent
        err = os.path.join(a.out, "errors", key + ".txt")
        if os.path.exists(err):
            os.remove(err)
        print(f"sweep.py: {key}: exit {p.returncode}, solved={rec.get('solved')}", file=sys.stderr)
        return 0
    os.makedirs(os.path.join(a.out, "errors"), exist_ok=True)
    with open(os.path.join(a.out, "errors", key + ".txt"), "w") as f:
        f.write(f"exit {p.returncode}: {shlex.join(cmd)}\n{p.stderr}")
    print(f"sweep.py: run {key} failed (exit {p.returncode}): {p.stderr.strip()[:300]}", file=sys.stderr)
    return 1


def progress(runs, out):
    done = len(runs) - len(pending_rows(runs, out))
    errs = os.path.join(out, "errors")
    failed = len(os.listdir(errs)) if os.path.isdir(errs) else 0
    return done, failed


def cmd_parallel(a):
    runs = read_runs(a.csv)
    if not shutil.which("parallel"):
        fail("GNU parallel is not installed (apt-get install parallel)")
    os.makedirs(a.out, exist_ok=True)
    # --resume-failed: jobs that succeeded are skipped, failed ones run again (a row fixed
    # in the CSV is picked up: the job is the row number).
    cmd = ["parallel", "--joblog", os.path.join(a.out, "joblog"), "--resume-failed", "-j", str(a.jobs)]
    if a.bar:
        cmd.append("--bar")
    if a.sshloginfile:
        # Remote hosts: same paths (shared file system); run in the same directory.
        cmd += ["--sshloginfile", a.sshloginfile, "--workdir", ROOT]
    cmd += [sys.executable, SELF, "run", os.path.abspath(a.csv), os.path.abspath(a.out), "{}", "--app",
            os.path.abspath(a.app), ":::", *map(str, range(1, len(runs) + 1))]
    rc = subprocess.run(cmd).returncode
    done, failed = progress(runs, a.out)
    print(f"sweep.py: {done}/{len(runs)} runs have results, {failed} failed; results in {a.out}/results",
          file=sys.stderr)
    return 0 if done == len(runs) else (rc or 1)


def cmd_slurm(a):
    runs = read_runs(a.csv)
    if not shutil.which("sbatch"):
        fail("sbatch not found (Slurm client tools)")
    rows = pending_rows(runs, a.out)
    if not rows:
        print(f"sweep.py: all {len(runs)} runs have results in {a.out}/results", file=sys.stderr)
        return 0
    os.makedirs(os.path.join(a.out, "slurm"), exist_ok=True)
    array = ",".join(map(str, rows))
    if a.max_parallel:
        array += f"%{a.max_parallel}"
    wrap = shlex.join([sys.executable, SELF, "run", os.path.abspath(a.csv), os.path.abspath(a.out),
                       "--app", os.path.abspath(a.app), "--row-from-env"])
    cmd = ["sbatch", "--parsable", f"--array={array}", "--job-name=rtlacam-sweep",
           f"--output={os.path.abspath(a.out)}/slurm/%A_%a.out", f"--chdir={ROOT}", *a.sbatch_args]
    if a.wait:
        cmd.append("--wait")
    cmd.append(f"--wrap={wrap}")
    print(f"sweep.py: submitting {len(rows)} of {len(runs)} runs: {shlex.join(cmd)}", file=sys.stderr)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, text=True)
    if p.stdout.strip():
        print(p.stdout.strip())  # the job id
    if a.wait:
        done, failed = progress(runs, a.out)
        print(f"sweep.py: {done}/{len(runs)} runs have results, {failed} failed; results in {a.out}/results",
              file=sys.stderr)
        return 0 if done == len(runs) else 1
    return p.returncode


def cmd_collect(a):
    runs = read_runs(a.csv)
    missing = 0
    for key, *_ in runs:
        try:
            with open(result_path(a.out, key)) as f:
                sys.stdout.write(f.read())
        except FileNotFoundError:
            missing += 1
    if missing:
        print(f"sweep.py: {missing} of {len(runs)} runs have no result yet", file=sys.stderr)
    return 0


def cmd_status(a):
    runs = read_runs(a.csv)
    done, failed = progress(runs, a.out)
    print(f"{done} done, {failed} failed, {len(runs) - done} pending of {len(runs)}")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)

    def common(p, app=True):
        p.add_argument("csv", help="the sweep: CSV with a key column, one run per row")
        p.add_argument("out", help="output directory (results/, errors/, joblog, slurm/)")
        if app:
            p.add_argument("--app", default=DEFAULT_APP, help="the app every row runs (default: rtlacam-bench)")

    p = sub.add_parser("run", help="one row (what the schedulers call)")
    common(p)
    p.add_argument("row", type=int, nargs="?", help="1-based row number")
    p.add_argument("--row-from-env", action="store_true", help="take the row from $SLURM_ARRAY_TASK_ID")
    p = sub.add_parser("parallel", help="every pending row through GNU parallel")
    common(p)
    p.add_argument("-j", "--jobs", type=int, default=os.cpu_count(), help="runs at a time per host")
    p.add_argument("--sshloginfile", help="GNU parallel's list of hosts (multi-host sweep)")
    p.add_argument("--bar", action="store_true", help="GNU parallel's progress bar (needs a terminal)")
    p = sub.add_parser("slurm", help="every pending row as one Slurm job array")
    common(p)
    p.add_argument("--wait", action="store_true", help="block until the array ends (sbatch --wait)")
    p.add_argument("--max-parallel", type=int, help="at most this many array tasks at once (%%N)")
    p.add_argument("sbatch_args", nargs="*", help="more sbatch options, after --")
    common(sub.add_parser("collect", help="all results, CSV order, one JSON line each"), app=False)
    common(sub.add_parser("status", help="counts of done / failed / pending runs"), app=False)
    a = ap.parse_args()
    if a.cmd == "run":
        if a.row_from_env:
            try:
                a.row = int(os.environ["SLURM_ARRAY_TASK_ID"])
            except (KeyError, ValueError):
                fail("--row-from-env: SLURM_ARRAY_TASK_ID is not set")
        if a.row is None:
            fail("run needs a ROW (or --row-from-env)")
    return {"run": cmd_run, "parallel": cmd_parallel, "slurm": cmd_slurm, "collect": cmd_collect,
            "status": cmd_status}[a.cmd](a)


if __name__ == "__main__":
    sys.exit(main())
