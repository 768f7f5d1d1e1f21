#!/usr/bin/env python3
"""The section of docs/t1-table.md on the default t₁, converged in the time step (issue 14, item 2):
`rocking t1 --json` (converged: `t1_steps`, `step_converged`) against `rocking t1 --single-step
--json` (one OAS at the step rule) and the thesis's Tables 4 and 5.

usage: tools/t1_converged_table.py FF_SINGLE.json FF_CONVERGED.json NF_SINGLE.json NF_CONVERGED.json
                                   SHARED_DIR
"""
import csv, math, os, statistics, sys
import json

ff_single, ff_conv, nf_single, nf_conv, shared = sys.argv[1:6]


def load(p):
    return {os.path.basename(r["file"]): r for r in json.load(open(p))}


def thesis_tables(path):
    rows = {}
    for line in open(path, encoding="utf-8"):
        parts = line.rstrip("\n").split("\t")
        if parts and (parts[0].startswith("FF-") or parts[0].startswith("NF-")) and len(parts) >= 9:
            try:
                rows[parts[0]] = dict(tp=float(parts[5]), t1=float(parts[6]))
            except ValueError:
                pass
    return rows


thesis = thesis_tables(os.path.join(shared, "seed/thesis-rocking-mechanisms.txt"))
index = {os.path.basename(r["file"]): r for r in csv.DictReader(open(os.path.join(shared, "records/fema-p695/index.csv")))}
ff1, ffc, nf1, nfc = load(ff_single), load(ff_conv), load(nf_single), load(nf_conv)
assert set(ff1) == set(ffc) and set(nf1) == set(nfc), "the single-step and converged rows name other records"
for rows in (ffc, nfc):
    for f, r in rows.items():
        assert r.get("t1_steps") and r.get("step_converged") is not None, f"{f}: not a converged row"


def fmt(x, d=3):
    return "–" if x is None else f"{x:.{d}f}"


def agreement(ratios):
    dev = [abs(x - 1) for x in ratios]
    return (f"median |ratio − 1| {100 * statistics.median(dev):.1f} %, beyond 10 %: {sum(d > 0.10 for d in dev)}, "
            f"beyond 15 %: {sum(d > 0.15 for d in dev)}, ours larger: {sum(x > 1 for x in ratios)} of {len(ratios)}")


def steps_cell(r):
    return ", ".join(f"×{f:g}: {fmt(t, 4)}" for f, t in r["t1_steps"])


def moved(single, conv):
    """Records whose converged t₁ differs from the step rule's by more than 10 %."""
    out = []
    for f, c in conv.items():
        s = single[f]
        if s["t1"] and c["t1"] and abs(c["t1"] / s["t1"] - 1) > 0.10:
            out.append(f)
    return sorted(out)


def final_steps(conv):
    counts = {}
    for r in conv.values():
        key = f"×{r['dt_factor']:g}" + ("" if r["step_converged"] else " (not converged)")
        counts[key] = counts.get(key, 0) + 1
    return ", ".join(f"{k}: {v}" for k, v in sorted(counts.items(), key=lambda kv: -float(kv[0].split()[0][1:])))


def pearson(pairs):
    return statistics.correlation([a for a, _ in pairs], [b for _, b in pairs])


w = print
w("## The default t₁: converged in the time step (`rocking t1`, issue 14 item 2)\n")
w("Since 2026-11-24 `rocking t1` computes t₁ converged in the time step: the OAS at the step rule, then at "
  "half the step, and again, until two successive t₁ agree within 10 % (`max/min − 1 ≤ 0.1`), at most four "
  "halvings; the row is the finest step's (`docs/t1-accuracy.md`). The tables above are the step rule's "
  "(`rocking t1 --single-step`, the default before), with their bands. Rows: "
  f"`{ff_conv}` and `{nf_conv}` (`rocking t1 RECORD... --threads 1 --json`, or `--converge-step 0.1` before "
  "it was the default, which computes the same rows); table: `tools/t1_converged_table.py`.\n")
w("### Far field, against Table 4\n")
w("| thesis id | record | thesis t₁ | step rule t₁ | converged t₁ | steps (dt factor: t₁) | converged | converged / thesis |")
w("|---|---|---:|---:|---:|---|---|---:|")
r_single, r_conv, pairs = [], [], []
for f in sorted(ffc, key=lambda f: int(index[f]["thesis_id"][3:])):
    meta, s, c = index[f], ff1[f], ffc[f]
    th = thesis.get(meta["thesis_id"], {}).get("t1")
    if th:
        r_single.append(s["t1"] / th)
        r_conv.append(c["t1"] / th)
    if c.get("t_p"):
        pairs.append((c["t_p"], c["t1"]))
    w(f"| {meta['thesis_id']} | {meta['station']} {meta['component']} | {fmt(th)} | {fmt(s['t1'])} | {fmt(c['t1'])} | "
      f"{steps_cell(c)} | {'yes' if c['step_converged'] else '**no**'} | {fmt(c['t1'] / th if th else None)} |")
w("")
w(f"**Against Table 4 (44 records):** the step rule's t₁: {agreement(r_single)}; the converged t₁: {agreement(r_conv)}.")
w("")
w(f"**Steps (far field):** the row's step {final_steps(ffc)}. Moved by more than 10 % from the step rule's t₁: "
  f"{', '.join(index[f]['thesis_id'] for f in moved(ff1, ffc)) or 'none'}.")
w("")
w(f"**Correlation of the converged t₁ with t_p (far field):** r = {pearson(pairs):.3f} (thesis 0.72).")
w("")
w("### Near field (56 rotated components), against Table 5 as a population\n")
nf_moved = moved(nf1, nfc)
nf_pairs = [(r["t_p"], r["t1"]) for r in nfc.values() if r.get("t_p")]
th_nf = sorted(v["t1"] for k, v in thesis.items() if k.startswith("NF-"))
ours = sorted(r["t1"] for r in nfc.values() if r["t1"])
single = sorted(r["t1"] for r in nf1.values() if r["t1"])
w("| statistic | step rule (FN/FP) | converged (FN/FP) | thesis Table 5 (as recorded) |")
w("|---|---:|---:|---:|")
for name, fn in [("median t₁ [s]", statistics.median), ("mean t₁ [s]", statistics.mean),
                 ("min t₁ [s]", min), ("max t₁ [s]", max)]:
    w(f"| {name} | {fn(single):.3f} | {fn(ours):.3f} | {fn(th_nf):.3f} |")
w("")
w(f"**Steps (near field):** the row's step {final_steps(nfc)}. Moved by more than 10 % from the step rule's t₁: "
  + (", ".join(f"{f} ({nf1[f]['t1']:.4f} → {nfc[f]['t1']:.4f} s; {steps_cell(nfc[f])})" for f in nf_moved) or "none")
  + f". Correlation of the converged t₁ with t_p: r = {pearson(nf_pairs):.3f} (thesis 0.90).")
not_conv = sorted(f for rows in (ffc, nfc) for f, r in rows.items() if not r["step_converged"])
w("")
halvings = max(len(r["t1_steps"]) - 1 for rows in (ffc, nfc) for r in rows.values())
w(f"**Not converged after {halvings} halvings:** {', '.join(not_conv) or 'none'} — of {len(ffc) + len(nfc)} records.")
