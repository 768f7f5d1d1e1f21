#!/bin/sh
# The dt-halving of docs/siconos.md, end to end (about an hour on a loaded 2-core machine, nearly
# all of it Siconos' 10-drum runs). Run from the repository's root; needs `python3-siconos`
# (Debian) and `cargo build --release --example drum_column`.
#
#   sh bench/siconos/sweep.sh            # everything below
#   SICONOS=0 sh bench/siconos/sweep.sh  # the library's sweeps only (seconds), then the tables
#   FINE=1 sh bench/siconos/sweep.sh     # also both codes at 0.125 ms on ten drums (+30-40 min)
#   OTHER=1 sh bench/siconos/sweep.sh    # also the other columns at 1 ms and the peer with its
#                                        # gaps linearised at the midpoint (+60-90 min)
set -e
B=bench/siconos
PY=/usr/bin/python3
if [ "${SICONOS:-1}" != 0 ]; then
    # Both codes at each step, one process at a time, in one run (CPU ratios under one load).
    nice -n 5 $PY $B/compare.py --quick --cases 0,2 --dt 0.001,0.0005,0.00025 \
        --out $B/results_dt.json
    if [ "${FINE:-0}" = 1 ]; then
        nice -n 5 $PY $B/compare.py --quick --cases 2 --dt 0.000125 --out $B/results_dt_0125.json
    fi
    if [ "${OTHER:-0}" = 1 ]; then
        nice -n 5 $PY $B/compare.py --quick --cases 1,3,4,5 --out $B/results_other.json
        nice -n 5 $PY $B/compare.py --quick --cases 2 --only siconos --dt 0.001,0.0005 \
            --siconos-args '--linearise mid' --out $B/results_mid.json
    fi
fi
# The library alone, down to 1/64 ms: its converged values (the reference of the errors).
$PY $B/compare.py --quick --cases 0,2 --only rocking \
    --dt 0.004,0.002,0.001,0.0005,0.00025,0.000125,0.0000625,0.00003125,0.000015625 \
    --out $B/results_dt_rocking.json
# The library as plain Moreau–Jean (Siconos' scheme), and each of its three differences alone.
$PY $B/compare.py --quick --cases 0,2 --only rocking --plain \
    --dt 0.001,0.0005,0.00025,0.000125,0.0000625,0.00003125,0.000015625,0.0000078125 \
    --out $B/results_dt_rocking_plain.json
for s in locate persistent projection; do
    $PY $B/compare.py --quick --cases 2 --only rocking --rocking-args "--$s 0" \
        --dt 0.001,0.0005,0.00025,0.000125,0.0000625,0.00003125,0.000015625 \
        --out $B/results_dt_rocking_${s}0.json
done
$PY $B/convergence.py $B/results_dt_rocking*.json $B/results_dt.json \
    $(ls $B/results_dt_0125.json 2>/dev/null)
