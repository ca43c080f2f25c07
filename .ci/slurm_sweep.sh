#!/usr/bin/env bash
# CI: the Slurm path of scripts/sweep.py on a real single-node Slurm (Debian's slurmctld,
# slurmd and munge, started here as root, stopped on exit). A small sweep runs once
# through GNU parallel and once as a Slurm job array; both must leave the same result
# files (same keys, same deterministic fields). Fails loudly: any problem exits non-zero
# with the daemons' logs.
#
#   .ci/slurm_sweep.sh [BUILD_DIR]      (default build; needs build/apps/rtlacam-bench)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
BENCH="$BUILD/apps/rtlacam-bench"
SWEEP="$ROOT/scripts/sweep.py"
PY=/usr/bin/python3

die() { echo "slurm_sweep: FAILED: $*" >&2; exit 1; }
[[ $(id -u) -eq 0 ]] || die "run as root (it starts munged, slurmctld and slurmd)"
[[ -x "$BENCH" ]] || die "$BENCH not built"
missing=()
for p in munge slurmctld slurmd slurm-client parallel; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  echo "slurm_sweep: installing ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

T=$(mktemp -d /tmp/rtlacam-slurm.XXXXXX)
chmod 755 "$T"
PIDS=()
cleanup() {
  local rc=$?
  for pid in "${PIDS[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [[ $rc -ne 0 ]]; then
    for f in "$T"/*.log; do [[ -f "$f" ]] && { echo "--- $f" >&2; tail -20 "$f" >&2; }; done
  fi
  rm -rf "$T"
  exit $rc
}
trap cleanup EXIT

# munge: a private key, socket and pid file (the system's /run/munge is left alone).
mkdir -p "$T/munge"
chmod 700 "$T/munge"
dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$T/munge/munge.key"
/usr/sbin/munged --force --foreground --key-file="$T/munge/munge.key" --socket="$T/munge/socket" \
  --pid-file="$T/munge/pid" --log-file="$T/munged.log" --seed-file="$T/munge/seed" >"$T/munged.out.log" 2>&1 &
PIDS+=($!)
for _ in $(seq 50); do [[ -S "$T/munge/socket" ]] && break; sleep 0.1; done
[[ -S "$T/munge/socket" ]] || die "munged did not start"

# Slurm: one node (this machine), one partition, its own ports, spool and state dirs.
HOST=$(hostname -s)
CPUS=$(nproc)
PORT0=$((17000 + RANDOM % 2000))
mkdir -p "$T/spool" "$T/state"
export SLURM_CONF="$T/slurm.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=rtlacamci
SlurmctldHost=$HOST
SlurmctldPort=$PORT0
SlurmdPort=$((PORT0 + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/socket
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SlurmdTimeout=30
NodeName=$HOST CPUs=$CPUS State=UNKNOWN
PartitionName=ci Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
/usr/sbin/slurmctld -D -i -f "$SLURM_CONF" >"$T/slurmctld.out.log" 2>&1 &
PIDS+=($!)
/usr/sbin/slurmd -D -f "$SLURM_CONF" >"$T/slurmd.out.log" 2>&1 &
PIDS+=($!)
for _ in $(seq 100); do
  state=$(sinfo -h -N -o '%t' 2>/dev/null | head -1 || true)
  [[ "$state" == idle* ]] && break
  sleep 0.2
done
[[ "$state" == idle* ]] || die "the Slurm node is not idle (state '${state:-none}')"
echo "slurm_sweep: single-node Slurm up ($HOST, $CPUS CPUs, port $PORT0)"

# The sweep: deterministic runs (expansion budgets alone: with a wall cutoff too, a run is
# timed and its refinement may decide by measured time), one unsolved (exit 4), one invalid
# input (exit 2: an error file, no result).
M=tests/data/planner/random-32-32-20.map
S=tests/data/planner/random-32-32-20-random-1.scen
{
  echo "key,map,scen,agents,solver,budget_expansions,cutoff_ms,max_steps,seed"
  for solver in rtlacam naive pibt lacam; do
    for n in 20 60; do echo "$solver-$n,$M,$S,$n,$solver,10,,100000,1"; done
  done
  echo "pibt-limit,$M,$S,60,pibt,10,,2,1"
  echo "bad-agents,$M,$S,100000,rtlacam,10,,100000,1"
} >"$T/sweep.csv"

start=$(date +%s%N)
rc=0
$PY "$SWEEP" slurm "$T/sweep.csv" "$T/slurm-out" --app "$BENCH" --wait >"$T/sbatch.log" 2>&1 || rc=$?
slurm_ms=$(( ($(date +%s%N) - start) / 1000000 ))
[[ $rc -eq 1 ]] || die "sweep.py slurm: expected exit 1 (one bad run), got $rc: $(cat "$T/sbatch.log")"
n_out=$(ls "$T/slurm-out/slurm" | wc -l)
[[ $n_out -eq 10 ]] || die "expected 10 Slurm array task logs, got $n_out"
start=$(date +%s%N)
rc=0
$PY "$SWEEP" parallel "$T/sweep.csv" "$T/par-out" --app "$BENCH" -j "$CPUS" >"$T/parallel.log" 2>&1 || rc=$?
par_ms=$(( ($(date +%s%N) - start) / 1000000 ))
[[ $rc -ne 0 ]] || die "sweep.py parallel: the bad run must fail the sweep"

# Same result files: same keys; the same fields except timings.
$PY - "$T/slurm-out" "$T/par-out" <<'EOF' || die "Slurm and GNU parallel results differ"
import json, os, sys
a, b = sys.argv[1], sys.argv[2]
ka = sorted(os.listdir(os.path.join(a, "results")))
kb = sorted(os.listdir(os.path.join(b, "results")))
assert ka == kb, (ka, kb)
assert len(ka) == 9 and "bad-agents.json" not in ka, ka
assert os.listdir(os.path.join(a, "errors")) == ["bad-agents.txt"] == os.listdir(os.path.join(b, "errors"))
# Timings: every measured *_ms field (wall and CPU); cutoff_ms is an input.
def timing(f):
    return f.endswith("_ms") and f != "cutoff_ms"
for k in ka:
    ra = json.load(open(os.path.join(a, "results", k)))
    rb = json.load(open(os.path.join(b, "results", k)))
    for f in set(ra) | set(rb):
        if not timing(f):
            assert ra.get(f) == rb.get(f), (k, f, ra.get(f), rb.get(f))
    assert ra["valid"], k
    assert ra["solved"] == (k != "pibt-limit.json"), k
print("slurm_sweep: Slurm and GNU parallel wrote the same", len(ka), "result files")
EOF
grep -q "agents" "$T/slurm-out/errors/bad-agents.txt" || die "the error file does not say what was wrong"

# Resume: a second Slurm submission only runs what has no result (the bad run).
$PY "$SWEEP" slurm "$T/sweep.csv" "$T/slurm-out" --app "$BENCH" --wait >"$T/sbatch2.log" 2>&1 || true
grep -q "submitting 1 of 10 runs" "$T/sbatch2.log" || die "slurm resume: $(cat "$T/sbatch2.log")"
echo "slurm_sweep: OK (10 runs: Slurm array ${slurm_ms} ms, GNU parallel ${par_ms} ms)"
