#!/usr/bin/env python3
"""Convergence of t1 in the time step over a record suite, from `rocking t1 --json --dt-factor F`.

usage: tools/t1_dt_convergence.py [--band 0.10] [--worst N] FACTOR=FILE.json [band:FILE.json ...]

Each FILE is a list of rows (one per record, as `rocking t1 --json` writes them, several sets may be
joined by giving several files with the same FACTOR). FACTOR is the dt factor relative to the rule
the rows were computed with (e.g. 1, 0.5, 0.25). For every pair of consecutive factors (a, a/2) it
prints the spread max/min - 1 of t1 per record, the records beyond the band, and the largest
spread; the coarsest factor whose spread to its half is within the band on every record is the
converged one. `band:FILE` reads the rows of `rocking t1 --band --json`: the nominal t1 at factor 1
and the member `half-step` at factor 0.5 (the band's level and size at f_min are the nominal's, so
the per-record table shows them for factor 1 then). With --worst N the per-record table keeps the
N records of largest spread (all records otherwise). Markdown on stdout.
"""
import json, os, sys
from collections import defaultdict

band = 0.10
worst_n = None
args = sys.argv[1:]
while args[:1] in (["--band"], ["--worst"]):
    if args[0] == "--band":
        band = float(args[1])
    else:
        worst_n = int(args[1])
    args = args[2:]
rows = defaultdict(dict)  # record -> factor -> row
for a in args:
    if a.startswith("band:"):
        for r in json.load(open(a[5:])):
            rows[r["record"]][1.0] = r
            half = dict(r, t1=r["band"]["half-step"])
            half.pop("seconds", None)
            rows[r["record"]].setdefault(0.5, half)
        continue
    f, path = a.split("=", 1)
    for r in json.load(open(path)):
        rows[r["record"]][float(f)] = r
factors = sorted({f for r in rows.values() for f in r}, reverse=True)
recs = sorted(rows)
out = []
w = out.append
w(f"t1 [s] of {len(recs)} records at dt factors {', '.join(f'{f:g}' for f in factors)}; "
  f"spread = max/min - 1 between a factor and its half; band {band:.0%}.\n")
w("| pair | records compared | max spread | record | median spread | beyond 5 % | beyond the band | records beyond |")
w("|---|---:|---:|---|---:|---:|---:|---|")
for a, b in zip(factors, factors[1:]):
    sp = {}
    for k in recs:
        if a in rows[k] and b in rows[k]:
            x, y = rows[k][a]["t1"], rows[k][b]["t1"]
            sp[k] = max(x, y) / min(x, y) - 1
    if not sp:
        continue
    worst = max(sp, key=sp.get)
    s = sorted(sp.values())
    beyond = sorted((k for k in sp if sp[k] > band), key=lambda k: -sp[k])
    w(f"| {a:g} vs {b:g} | {len(sp)} | {sp[worst]*100:.1f} % | {worst} | {s[len(s)//2]*100:.1f} % | "
      f"{sum(v > 0.05 for v in sp.values())} | {len(beyond)} | {', '.join(f'{k} ({sp[k]*100:.1f} %)' for k in beyond) or '–'} |")
w("")
def spread(r):
    ts = [r[f]["t1"] for f in r]
    return max(ts) / min(ts) - 1
shown = sorted(recs, key=lambda k: -spread(rows[k]))[:worst_n] if worst_n else recs
if worst_n:
    w(f"The {len(shown)} records of largest spread over all factors:\n")
w("| record | " + " | ".join(f"t1 at x{f:g}" for f in factors) + " | level at f_min | R at f_min [m] |")
w("|---|" + "---:|" * len(factors) + "---:|---:|")
for k in shown:
    r = rows[k]
    finest = r[min(r)]
    w(f"| {k} | " + " | ".join(f"{r[f]['t1']:.4f}" if f in r else "" for f in factors)
      + f" | {finest['level_at_f_min']:.2f} | {finest['size_at_f_min']:.3f} |")
secs = {f: sum(r[f]["seconds"] for r in rows.values() if f in r and "seconds" in r[f]) for f in factors}
if any(secs.values()):
    w("")
    w("Sum of the per-record wall times (the rows' `seconds`, machine shared; a `band:` row's is "
      "that of its five spectra): " + ", ".join(f"x{f:g}: {secs[f]:.0f} s" for f in factors if secs[f]) + ".")
print("\n".join(out))
