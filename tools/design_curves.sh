#!/usr/bin/env bash
# The figures and data of docs/design-curves.md: `rocking suite` on the FEMA P695 far-field (44)
# and near-field (56) records with the default options. About 33 min on 2 busy cores (1951 s wall,
# 857 s CPU at the default step of 2026-11-23; docs/design-curves.md).
#   tools/design_curves.sh [SHARED_DIR]      (default ../shared)
set -euo pipefail
shared=${1:-../shared}
records=$shared/records/fema-p695
rocking=${ROCKING:-target/release/rocking}
mkdir -p docs/data/suite docs/figures
nice "$rocking" suite "$records"/farfield/*.AT2 --name "far field (FEMA P695, 44)" \
  --svg docs/figures/suite-farfield --csv docs/data/suite/farfield | tee docs/data/suite/farfield.txt
nice "$rocking" suite "$records"/nearfield_pulse/*.AT2 "$records"/nearfield_no_pulse/*.AT2 \
  --name "near field (FEMA P695, 56)" \
  --svg docs/figures/suite-nearfield --csv docs/data/suite/nearfield | tee docs/data/suite/nearfield.txt
rm -f docs/data/suite/*-records.csv  # every record's OAS: large, and in `rocking suite --json`
