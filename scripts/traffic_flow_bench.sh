#!/usr/bin/env bash
# Online traffic-flow guide paths (--traffic-flow on, planner/traffic_flow.hpp) against
# epibt with arrows alone, rotation model, LoRR 2023 MR23 (roundrobin), in one session:
# errands/step (mean, min-max over SEEDS), ratio to the first variant and to the LoRR best,
# planner wall ms and CPU p99 per step (plannerCpuTimeStats) against the budget.
# Defaults: INSTANCES "04 03 05 07 08", SEEDS "0 1 2", BUDGET 100 (ms), OUT out/traffic_flow;
# VARIANTS (';'-separated "name=rtlacam-lifelong options", the first is the baseline) as
# below; extra weights e.g. VARIANTS="...;tf-2=--solver epibt --traffic-flow on --tf-weights 2,0.25".
# epibt's decisions and the guide-path work are independent of the clock unless a step
# reaches its deadline (guide work then waits for the next step): numbers reproduce at any
# load unless preemption pushes a step past 100 ms wall. Run from the repository root
# after building rtlacam-lifelong (Release); the table is in $OUT/table.md.
set -euo pipefail
cd "$(dirname "$0")/.."
export OUT=${OUT:-out/traffic_flow}
export SEEDS=${SEEDS:-"0 1 2"}
export VARIANTS=${VARIANTS:-"epibt-arrows=--solver epibt --traffic-flow off;epibt-arrows-tf=--solver epibt --traffic-flow on"}
exec scripts/epibt_bench.sh
