#!/bin/sh
# CTest: rtlacam-lifelong writes a LoRR log, scripts/check_lorr_log.py reads it the way
# PlanViz does and replays it the way LoRR checks it.
#   planviz_log_test.sh PYTHON BIN CHECKER PROBLEM MAP MODEL STEPS [EXTRA OPTIONS]
set -eu
PY=$1 BIN=$2 CHECK=$3 PROBLEM=$4 MAP=$5 MODEL=$6 STEPS=$7 EXTRA=${8:-}
LOG=$(mktemp /tmp/rtlacam-planviz-XXXXXX.json)
trap 'rm -f "$LOG"' EXIT
"$BIN" --problem "$PROBLEM" --action-model "$MODEL" --steps "$STEPS" --budget-ms 5 --budget-expansions 50 --quiet --out "$LOG" $EXTRA > /dev/null
"$PY" "$CHECK" --map "$MAP" --plan "$LOG"
