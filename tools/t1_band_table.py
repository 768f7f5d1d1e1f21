#!/usr/bin/env python3
"""The t₁ band of the FEMA P695 records (against the thesis's Table 4 for the far field): a
markdown section from `rocking t1 --band --json` outputs (one or more shard files).

usage: tools/t1_band_table.py SHARED_DIR BAND.json [BAND.json ...] >> docs/t1-table.md

Per record: the thesis's t₁, ours (nominal), the band [min, max] over the five spectra of
`--band`, its width relative to the nominal t₁, the conservative t₁ (f_min of the envelope), and
whether the thesis's value lies inside the band. Records without a thesis id (the near-field
components, rotated FN/FP) are listed by name after the far-field ones, with no thesis value.
"""
import csv, json, os, statistics, sys

sys.path.insert(0, os.path.dirname(__file__))
shared, files = sys.argv[1], sys.argv[2:]


def thesis_t1(path):
    rows = {}
    for line in open(path, encoding="utf-8"):
        parts = line.rstrip("\n").split("\t")
        if parts and parts[0].startswith("FF-") and len(parts) >= 9:
            try:
                rows[parts[0]] = float(parts[6])
            except ValueError:
                pass
    return rows


thesis = thesis_t1(os.path.join(shared, "seed/thesis-rocking-mechanisms.txt"))
index = {os.path.basename(r["file"]): r for r in csv.DictReader(open(os.path.join(shared, "records/fema-p695/index.csv")))}
rows = [r for f in files for r in json.load(open(f))]
def tid_of(r):
    return index.get(os.path.basename(r["file"]), {}).get("thesis_id", "")


rows.sort(key=lambda r: (0, int(tid_of(r)[3:]), "") if tid_of(r).startswith("FF-") else (1, 0, r["record"]))

out = []
w = out.append
w("| thesis id | record | thesis t₁ | ours t₁ | band [min, max] | width | conservative t₁ | half step | levels shifted | sizes shifted | other locator | thesis inside |")
w("|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---|")
widths, inside, below_cons, n = [], 0, 0, 0
for r in rows:
    tid = tid_of(r) if tid_of(r).startswith("FF-") else os.path.basename(r["file"]).removesuffix(".AT2")
    th = thesis.get(tid)
    lo, hi = r["t1_range"]
    width = (hi - lo) / r["t1"]
    widths.append(width)
    b = r["band"]
    ins = th is not None and lo <= th <= hi
    if th is not None:
        n += 1
        inside += ins
        below_cons += th <= r["t1_conservative"]
    w(f"| {tid} | {r['record']} | {'–' if th is None else f'{th:.3f}'} | {r['t1']:.3f} | [{lo:.3f}, {hi:.3f}] | {100 * width:.1f} % | "
      f"{r['t1_conservative']:.3f} | {b['half-step']:.3f} | {b['levels-shifted']:.3f} | {b['sizes-shifted']:.3f} | "
      f"{b['other-locator']:.3f} | {'–' if th is None else 'yes' if ins else 'no'} |")
w("")
w(f"{len(rows)} records. Band width (max − min) / nominal t₁: median {100 * statistics.median(widths):.1f} %, "
  f"max {100 * max(widths):.1f} %, min {100 * min(widths):.1f} %."
  + (f" Table 4's t₁ inside our band: {inside} of {n}; at or below our conservative t₁: {below_cons} of {n}." if n else ""))
print("\n".join(out))
