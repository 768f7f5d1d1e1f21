#!/usr/bin/env bash
# docs/t1-table.md from the stored rows (no simulation): tools/t1_table.py (the tables against
# Tables 4 and 5, the band on the records that have one, the procedure variants),
# tools/t1_converged_table.py (the default t₁, converged in the step) and
# tools/t1_band_table.py (each band member per record).
#   tools/t1_doc.sh [SHARED_DIR]      (default ../shared)
set -euo pipefail
shared=${1:-../shared}
d=docs/data
variants=()
for v in record-end strong-motion record-dt levels-open levels-log; do
  [ -f "$d/t1-farfield-$v.json" ] && variants+=("$v=$d/t1-farfield-$v.json")
done
bands=("$d"/t1-band/*.json)
{
  python3 tools/t1_table.py "$d/t1-farfield.json" "$d/t1-nearfield.json" "$shared" \
    --band "${bands[@]}" --explain "$d/t1-farfield-explain.json" "${variants[@]}"
  echo
  python3 tools/t1_converged_table.py "$d/t1-dt/converge/farfield-default.json" \
    "$d/t1-dt/converge/farfield-converge.json" "$d/t1-nearfield.json" \
    "$d/t1-dt/converge/nearfield-converge.json" "$shared"
  echo
  echo "## t₁'s band per record: each member (issue 14 item 3)"
  echo
  echo "Rows: \`rocking t1 RECORD... --band --json\` (\`docs/data/t1-band/\`; the far field run as eight"
  echo "\`--shard i/8\` pieces on this machine, 07:02–07:42 on 2026-11-23, the near field (its 56 records"
  echo "sorted by path) as eight \`--shard i/8\` pieces, 12:13–13:11 on 2026-11-23, joined by"
  echo "\`rocking t1 --merge\`; both at the current default step, the near field with commit 0359335). The band is t₁ over five"
  echo "spectra a careful analyst would call equivalent: as computed, half the time step, the level grid"
  echo "shifted by half a cell, the size grid shifted by half a cell, the other event locator"
  echo "(\`docs/spectra.md\`); the conservative t₁ is i_cr / f_min of the envelope of the five, i.e. the"
  echo "band's upper end. Table: \`tools/t1_band_table.py $shared docs/data/t1-band/*.json\`."
  echo
  python3 tools/t1_band_table.py "$shared" "${bands[@]}"
} > docs/t1-table.md
