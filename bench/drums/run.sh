#!/bin/sh
# The full drum suite (docs/multidrum.md, "The drum suite") in 16 shards, two processes at a
# time, then its figures:  bench/drums/run.sh ROCKING_BINARY OUT_DIR [RECORDS_DIR]
# Every run is deterministic; the shards' union is the suite whatever their order.
# BENCH_FLAGS passes options of the scheme, e.g. BENCH_FLAGS=--consistent (consistent_sweeps_suite.csv;
# BENCH_FLAGS="--consistent --energy-tol 1e-6" is consistent_control_suite.csv, docs/energy-every-run.md;
# consistent_gap_suite.csv is the option before the sweeps of its cycling problems;
# consistent_suite.csv is the option before its impact gap tolerance).
set -e
BIN=${1:?rocking binary}; OUT=${2:?output folder}
REC=${3:-../shared/records/fema-p695/farfield}
mkdir -p "$OUT"
run() {
  /usr/bin/time -v -o "$OUT/full_$1.time" nice -n 10 "$BIN" bench drums --records "$REC" \
    --threads 1 --shard "$1/16" --csv "$OUT/full_$1.csv" ${BENCH_FLAGS:-} > "$OUT/full_$1.txt"
}
( for i in 0 2 4 6 8 10 12 14; do run $i; done ) &
( for i in 1 3 5 7 9 11 13 15; do run $i; done ) &
wait
python3 "$(dirname "$0")/analyse.py" --merge "$OUT/full_suite.csv" \
  $(for i in $(seq 0 15); do echo "$OUT/full_$i.csv"; done)
